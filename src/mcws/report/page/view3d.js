// The report page's 3-D view on three.js (r111): the scene's layers (meshes, points, voxels),
// the robot's bodies and their animations, decoded from the embedded base64 arrays.
mcws.littleEndian = new Uint8Array(new Uint32Array([1]).buffer)[0] === 1;

mcws.decodeBytes = function (text) {
  const binary = atob(text || "");
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return bytes;
};

// Little-endian float32 (or uint32) words from base64.
mcws.decodeWords = function (text, Type) {
  const bytes = mcws.decodeBytes(text);
  if (mcws.littleEndian) return new Type(bytes.buffer, 0, bytes.length / 4);
  const view = new DataView(bytes.buffer), out = new Type(bytes.length / 4);
  const float = Type === Float32Array;
  for (let i = 0; i < out.length; ++i) out[i] = float ? view.getFloat32(4 * i, true) : view.getUint32(4 * i, true);
  return out;
};

// Viridis, sampled at five points.
mcws.colourStops = [[0.267, 0.005, 0.329], [0.229, 0.322, 0.546], [0.128, 0.567, 0.551],
                    [0.369, 0.789, 0.383], [0.993, 0.906, 0.144]];

mcws.colourAt = function (t) {
  const s = Math.min(1, Math.max(0, isFinite(t) ? t : 0)) * (mcws.colourStops.length - 1);
  const i = Math.min(Math.floor(s), mcws.colourStops.length - 2), f = s - i;
  const a = mcws.colourStops[i], b = mcws.colourStops[i + 1];
  return [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])];
};

mcws.valueColours = function (layer, values) {
  const colours = new Float32Array(values.length * 3);
  const span = layer.value_max - layer.value_min;
  for (let i = 0; i < values.length; ++i) {
    const c = mcws.colourAt(span > 0 ? (values[i] - layer.value_min) / span : 0.5);
    colours[3 * i] = c[0]; colours[3 * i + 1] = c[1]; colours[3 * i + 2] = c[2];
  }
  return colours;
};

mcws.meshObject = function (positions, triangles, colour, opacity, colours) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  if (triangles.length > 0) geometry.setIndex(new THREE.BufferAttribute(triangles, 1));
  if (colours) geometry.setAttribute("color", new THREE.BufferAttribute(colours, 3));
  geometry.computeVertexNormals();
  const material = new THREE.MeshLambertMaterial({
    color: colours ? 0xffffff : new THREE.Color(colour[0], colour[1], colour[2]),
    vertexColors: colours ? THREE.VertexColors : THREE.NoColors, side: THREE.DoubleSide,
    transparent: opacity < 1, opacity: opacity, depthWrite: opacity >= 1});
  return new THREE.Mesh(geometry, material);
};

mcws.pointsObject = function (layer, positions, colours) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  if (colours) geometry.setAttribute("color", new THREE.BufferAttribute(colours, 3));
  const c = layer.color;
  return new THREE.Points(geometry, new THREE.PointsMaterial({
    size: layer.size, sizeAttenuation: true, color: colours ? 0xffffff : new THREE.Color(c[0], c[1], c[2]),
    vertexColors: colours ? THREE.VertexColors : THREE.NoColors, transparent: layer.opacity < 1,
    opacity: layer.opacity}));
};

// Voxels: one cube drawn once per voxel (instanced), shaded by the facing of its sides.
mcws.voxelsObject = function (layer, positions, colours) {
  const box = new THREE.BoxBufferGeometry(1, 1, 1);
  const geometry = new THREE.InstancedBufferGeometry();
  geometry.setIndex(box.index);
  geometry.setAttribute("position", box.attributes.position);
  geometry.setAttribute("normal", box.attributes.normal);
  geometry.setAttribute("offset", new THREE.InstancedBufferAttribute(positions, 3));
  if (!colours) {
    colours = new Float32Array(positions.length);
    for (let i = 0; i < colours.length; ++i) colours[i] = layer.color[i % 3];
  }
  geometry.setAttribute("voxelColour", new THREE.InstancedBufferAttribute(colours, 3));
  geometry.maxInstancedCount = positions.length / 3;
  const material = new THREE.ShaderMaterial({
    uniforms: {edge: {value: layer.size}, opacity: {value: layer.opacity}},
    vertexShader: "attribute vec3 offset; attribute vec3 voxelColour; uniform float edge;\n" +
      "varying vec3 vColour; varying vec3 vNormal;\n" +
      "void main() { vColour = voxelColour; vNormal = normalize(normalMatrix * normal);\n" +
      "  gl_Position = projectionMatrix * modelViewMatrix * vec4(offset + position * edge, 1.0); }",
    fragmentShader: "uniform float opacity; varying vec3 vColour; varying vec3 vNormal;\n" +
      "void main() { gl_FragColor = vec4(vColour * (0.55 + 0.45 * abs(vNormal.z)), opacity); }",
    transparent: layer.opacity < 1, depthWrite: layer.opacity >= 1});
  const mesh = new THREE.Mesh(geometry, material);
  mesh.frustumCulled = false;  // the bounding sphere three.js sees is that of one cube
  return mesh;
};

mcws.layerObject = function (layer, positions) {
  const colours = layer.values ? mcws.valueColours(layer, mcws.decodeWords(layer.values, Float32Array)) : null;
  if (layer.kind === "mesh")
    return mcws.meshObject(positions, mcws.decodeWords(layer.triangles, Uint32Array), layer.color, layer.opacity, colours);
  if (layer.kind === "voxels") return mcws.voxelsObject(layer, positions, colours);
  return mcws.pointsObject(layer, positions, colours);
};

mcws.groupedNumber = function (n) {
  return String(n).replace(/\B(?=(\d{3})+(?!\d))/g, "\u202f");
};

mcws.colourBar = function (layer, unit) {
  const bar = mcws.element("div", {"class": "colour-bar"});
  bar.appendChild(mcws.element("div", {}, layer.name + ": " + mcws.withUnit(layer.value_label || "value", layer.value_unit)));
  const stops = mcws.colourStops.map(function (c) {
    return "rgb(" + c.map(function (v) { return Math.round(255 * v); }).join(",") + ")";
  });
  bar.appendChild(mcws.element("div", {"class": "bar", style: "background: linear-gradient(to right, " + stops.join(", ") + ")"}));
  const ends = mcws.element("div", {"class": "ends"});
  ends.appendChild(mcws.element("span", {}, mcws.formatNumber(layer.value_min)));
  ends.appendChild(mcws.element("span", {}, mcws.formatNumber(layer.value_max)));
  bar.appendChild(ends);
  return bar;
};

// The layer list (a checkbox per layer), the colour bars of the layers with values, and the
// note of the layers the page decimated.
mcws.layerControls = function (view) {
  const list = document.getElementById("layer-list"), bars = document.getElementById("colour-bars");
  const cut = document.getElementById("decimation");
  view.layers.forEach(function (entry) {
    const layer = entry.data, item = mcws.element("li"), label = mcws.element("label");
    const box = mcws.element("input", {type: "checkbox", "data-layer": layer.name});
    box.checked = layer.visible;
    const c = layer.values ? mcws.colourAt(0.5) : layer.color;
    label.appendChild(box);
    label.appendChild(mcws.element("span", {"class": "swatch", style: "background: rgb(" +
      c.map(function (v) { return Math.round(255 * v); }).join(",") + ")"}));
    label.appendChild(document.createTextNode(layer.name));
    item.appendChild(label);
    list.appendChild(item);
    if (layer.values) { entry.bar = mcws.colourBar(layer); bars.appendChild(entry.bar); entry.bar.hidden = !layer.visible; }
    box.addEventListener("change", function () { view.setLayerVisible(layer.name, box.checked); });
    if (layer.points < layer.total_points)
      cut.appendChild(mcws.element("p", {}, layer.name + ": " + mcws.groupedNumber(layer.points) + " of " +
                                   mcws.groupedNumber(layer.total_points) + " shown (the page keeps every " +
                                   Math.ceil(layer.total_points / Math.max(1, layer.points)) + "th)"));
  });
};

// The bounding sphere of the visible layers' points and of the bodies as they stand.
mcws.boundingSphere = function (view) {
  const box = new THREE.Box3();
  view.layers.forEach(function (entry) {
    if (entry.positions.length >= 3) box.union(new THREE.Box3().setFromArray(entry.positions));
  });
  view.bodies.forEach(function (body) { body.updateMatrixWorld(true); box.expandByObject(body); });
  if (box.isEmpty()) return new THREE.Sphere(new THREE.Vector3(), 1);
  const sphere = box.getBoundingSphere(new THREE.Sphere());
  if (!(sphere.radius > 0)) sphere.radius = 1;
  return sphere;
};
