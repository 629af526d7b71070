// The report page's 3-D view (renderer, camera, orbit controls, layers, bodies, the path
// animations), its controls, and the page's start with its test hook window.mcwsReport.
mcws.View = function (data, canvas) {
  this.scene = new THREE.Scene();
  this.scene.background = new THREE.Color(0xf4f5f7);
  this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
  this.camera.up.set(0, 0, 1);
  this.scene.add(new THREE.AmbientLight(0xffffff, 0.55));
  const light = new THREE.DirectionalLight(0xffffff, 0.6);
  light.position.set(0.4, 0.6, 1);
  light.target.position.set(0, 0, -1);
  this.camera.add(light, light.target);  // a head light: it turns with the camera
  this.scene.add(this.camera);
  this.layers = data.layers.map(function (layer) {
    const positions = mcws.decodeWords(layer.positions, Float32Array);
    const object = mcws.layerObject(layer, positions);
    object.visible = layer.visible;
    this.scene.add(object);
    return {data: layer, positions: positions, object: object};
  }, this);
  this.bodies = data.bodies.map(function (body) {
    const mesh = mcws.meshObject(mcws.decodeWords(body.positions, Float32Array),
                                 mcws.decodeWords(body.triangles, Uint32Array), body.color, 1, null);
    mesh.matrixAutoUpdate = false;
    mesh.name = body.name;
    this.scene.add(mesh);
    return mesh;
  }, this);
  this.animations = data.animations.map(function (animation) {
    return {data: animation, poses: mcws.decodeWords(animation.poses, Float32Array),
            parameter: mcws.decodeWords(animation.parameter, Float32Array)};
  });
  this.animation = 0;
  this.frame = 0;
  this.renderCount = 0;
  this.renderer = null;
  this.onFrame = function () {};
  this.setFrame(0);
};

// Draws on `canvas` (false when the browser gives no WebGL: the view stays empty).
mcws.View.prototype.attach = function (canvas) {
  // Asked first: three.js would log an error for a browser without WebGL.
  const probe = document.createElement("canvas");
  const gl = window.WebGLRenderingContext && (probe.getContext("webgl") || probe.getContext("experimental-webgl"));
  if (!gl) return false;
  const info = gl.getExtension("WEBGL_debug_renderer_info");
  const software = /swiftshader|llvmpipe|software/i.test(info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : "");
  const lose = gl.getExtension("WEBGL_lose_context");
  if (lose) lose.loseContext();
  try {
    // Without a GPU (SwiftShader) antialiasing doubles the time of a large point cloud's frame.
    this.renderer = new THREE.WebGLRenderer({canvas: canvas, antialias: !software, preserveDrawingBuffer: true});
  } catch (e) {
    return false;
  }
  this.renderer.setPixelRatio(1);
  this.canvas = canvas;
  this.controls = new THREE.OrbitControls(this.camera, canvas);
  this.fit();
  this.controls.addEventListener("change", this.render.bind(this));
  window.addEventListener("resize", this.resize.bind(this));
  this.resize();
  return true;
};

mcws.View.prototype.fit = function () {
  const sphere = mcws.boundingSphere(this);
  const distance = sphere.radius / Math.sin(THREE.Math.degToRad(this.camera.fov / 2)) * 0.9;
  const direction = new THREE.Vector3(1.0, -1.4, 0.9).normalize();
  this.camera.position.copy(sphere.center).addScaledVector(direction, distance);
  this.camera.near = distance / 200;
  this.camera.far = distance * 20;
  this.camera.updateProjectionMatrix();
  this.controls.target.copy(sphere.center);
  this.controls.update();
};

mcws.View.prototype.resize = function () {
  const width = this.canvas.clientWidth || 800, height = this.canvas.clientHeight || 520;
  this.renderer.setSize(width, height, false);
  this.camera.aspect = width / height;
  this.camera.updateProjectionMatrix();
  this.render();
};

mcws.View.prototype.render = function () {
  if (!this.renderer) return;
  this.renderer.render(this.scene, this.camera);
  ++this.renderCount;
};

// Turns the camera about the vertical through the orbit's centre [degree].
mcws.View.prototype.rotate = function (degrees) {
  if (!this.controls) return;
  const offset = this.camera.position.clone().sub(this.controls.target);
  offset.applyAxisAngle(this.camera.up, THREE.Math.degToRad(degrees));
  this.camera.position.copy(this.controls.target).add(offset);
  this.controls.update();
  this.render();
};

// Places every body as frame k of the animation shown (identity without animations).
mcws.View.prototype.setFrame = function (k) {
  const animation = this.animations[this.animation];
  const frames = animation ? animation.data.frames : 1;
  this.frame = Math.min(Math.max(0, Math.round(k) || 0), Math.max(0, frames - 1));
  this.bodies.forEach(function (body, i) {
    if (animation && frames > 0) body.matrix.fromArray(animation.poses, (this.frame * this.bodies.length + i) * 16);
    else body.matrix.identity();
    body.matrixWorldNeedsUpdate = true;
  }, this);
  this.onFrame();
  this.render();
};

mcws.View.prototype.selectAnimation = function (index) {
  this.animation = Math.min(Math.max(0, index), Math.max(0, this.animations.length - 1));
  this.setFrame(0);
};

mcws.View.prototype.setLayerVisible = function (name, visible) {
  this.layers.forEach(function (entry) {
    if (entry.data.name !== name) return;
    entry.object.visible = visible;
    if (entry.bar) entry.bar.hidden = !visible;
    const box = document.querySelector('input[data-layer="' + CSS.escape(name) + '"]');
    if (box) box.checked = visible;
  });
  this.render();
};

mcws.View.prototype.bodyPosition = function (i) {
  const body = this.bodies[i];
  body.updateMatrixWorld(true);
  const p = new THREE.Vector3().setFromMatrixPosition(body.matrixWorld);
  return [p.x, p.y, p.z];
};

// The path control: which animation, play/pause, the frame slider, the frame's parameter.
mcws.animationControls = function (view) {
  if (view.animations.length === 0) return;
  const select = document.getElementById("animation-select"), slider = document.getElementById("animation-slider");
  const play = document.getElementById("animation-play"), text = document.getElementById("animation-frame");
  document.getElementById("animation-control").hidden = false;
  view.animations.forEach(function (animation, i) {
    select.appendChild(mcws.element("option", {value: i}, animation.data.name));
  });
  view.onFrame = function () {
    const animation = view.animations[view.animation], data = animation.data;
    slider.max = Math.max(0, data.frames - 1);
    slider.value = view.frame;
    let line = "frame " + (view.frame + 1) + " of " + data.frames;
    if (animation.parameter.length > view.frame)
      line += ", " + (data.parameter_label || "parameter") + " = " + mcws.formatNumber(animation.parameter[view.frame]) +
              (data.parameter_unit ? " " + data.parameter_unit : "");
    text.textContent = line;
  };
  view.onFrame();
  let timer = null;
  const stop = function () { clearInterval(timer); timer = null; play.textContent = "Play"; };
  select.addEventListener("change", function () { stop(); view.selectAnimation(Number(select.value)); });
  slider.addEventListener("input", function () { stop(); view.setFrame(Number(slider.value)); });
  play.addEventListener("click", function () {
    if (timer !== null) return stop();
    play.textContent = "Pause";
    timer = setInterval(function () {
      const frames = view.animations[view.animation].data.frames;
      view.setFrame((view.frame + 1) % Math.max(1, frames));
    }, 100);
  });
};

// The test hook: what a browser test asks the page.
mcws.hook = function (hook, view) {
  hook.rotate = function (degrees) { view.rotate(degrees); };
  hook.setFrame = function (k) { view.setFrame(k); return view.frame; };
  hook.frame = function () { return view.frame; };
  hook.selectAnimation = function (i) { view.selectAnimation(i); };
  hook.bodyCount = function () { return view.bodies.length; };
  hook.bodyPosition = function (i) { return view.bodyPosition(i); };
  hook.layerNames = function () { return view.layers.map(function (e) { return e.data.name; }); };
  hook.setLayerVisible = function (name, visible) { view.setLayerVisible(name, visible); };
  hook.renderCount = function () { return view.renderCount; };
};

// The answers and sections first; the 3-D view once they are on the screen (a large scene takes
// a while to upload and draw without a GPU).
(function () {
  const hook = window.mcwsReport = {ready: false, webgl: false, error: null};
  const fail = function (e) {
    hook.error = String(e && e.stack || e);
    console.error("mcws report: " + hook.error);
  };
  try {
    const report = JSON.parse(document.getElementById("mcws-report").textContent);
    const view = report.view || {};
    if (view.title) document.getElementById("title").textContent = view.title;
    mcws.renderAnswers(report, view.answers || [], document.getElementById("answers"));
    mcws.renderSections(report, view.sections || [], document.getElementById("sections"));
  } catch (e) {
    return fail(e);
  }
  requestAnimationFrame(function () { setTimeout(function () {
    try {
      const data = JSON.parse(document.getElementById("mcws-scene").textContent);
      document.getElementById("length-unit").textContent = data.length_unit || "the robot's unit";
      const scene = new mcws.View(data);
      mcws.layerControls(scene);
      mcws.animationControls(scene);
      hook.webgl = scene.attach(document.getElementById("scene-canvas"));
      if (!hook.webgl) {
        const note = document.getElementById("webgl-error");
        note.textContent = "This browser gives no WebGL: the 3-D view cannot be drawn (the rest of the report is shown).";
        note.hidden = false;
      }
      mcws.hook(hook, scene);
      hook.readyMs = performance.now();  // since the navigation started [ms]
      hook.ready = true;
    } catch (e) {
      fail(e);
    }
  }, 0); });
})();
