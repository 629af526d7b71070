// The report page's text part: numbers, the answers at the top and the sections (table, image,
// chart, timeline, text), all read from the report's JSON. Every number shown carries
// data-source, the JSON pointer (RFC 6901) of the value it shows.
var mcws = {};

// Up to 6 significant digits, in JavaScript's own shortest form ("-5", "0.95", "1.23457e+21").
mcws.formatNumber = function (value) {
  if (typeof value !== "number") return value === null || value === undefined ? "n/a" : String(value);
  return String(Number(value.toPrecision(6)));
};

// The value at an RFC 6901 pointer, or undefined when the document has none there.
mcws.resolvePointer = function (document, pointer) {
  if (pointer === "") return document;
  if (typeof pointer !== "string" || pointer[0] !== "/") return undefined;
  let node = document;
  for (const raw of pointer.slice(1).split("/")) {
    const key = raw.replace(/~1/g, "/").replace(/~0/g, "~");
    if (node === null || typeof node !== "object" || !Object.prototype.hasOwnProperty.call(node, key))
      return undefined;
    node = node[key];
  }
  return node;
};

mcws.escapePointer = function (key) {
  return String(key).replace(/~/g, "~0").replace(/\//g, "~1");
};

mcws.element = function (tag, attributes, text) {
  const node = document.createElement(tag);
  for (const name in attributes || {}) node.setAttribute(name, attributes[name]);
  if (text !== undefined) node.textContent = text;
  return node;
};

mcws.svgElement = function (tag, attributes, text) {
  const node = document.createElementNS("http://www.w3.org/2000/svg", tag);
  for (const name in attributes || {}) node.setAttribute(name, attributes[name]);
  if (text !== undefined) node.textContent = text;
  return node;
};

// A number read from the report at `pointer`, shown formatted, with data-source.
mcws.numberSpan = function (report, pointer) {
  return mcws.element("span", {"class": "number", "data-source": pointer},
                      mcws.formatNumber(mcws.resolvePointer(report, pointer)));
};

mcws.withUnit = function (name, unit) {
  return unit ? name + " [" + unit + "]" : name;
};

// The answers: label, value with unit, optional 95 % interval and note.
mcws.renderAnswers = function (report, answers, container) {
  answers.forEach(function (answer, i) {
    const own = "/view/answers/" + i;
    container.appendChild(mcws.element("div", {"class": "label"}, answer.label || ""));
    const cell = mcws.element("div", {"class": "value-cell"});
    const source = typeof answer.source === "string" ? answer.source : own + "/value";
    const value = mcws.numberSpan(report, source);
    value.classList.add("value");
    cell.appendChild(value);
    if (answer.unit) cell.appendChild(mcws.element("span", {"class": "unit"}, " " + answer.unit));
    if (Array.isArray(answer.interval)) {
      const base = typeof answer.interval_source === "string" ? answer.interval_source
                                                               : own + "/interval";
      const interval = mcws.element("span", {"class": "interval"}, "  (95 % interval ");
      interval.appendChild(mcws.numberSpan(report, base + "/0"));
      interval.appendChild(document.createTextNode(" to "));
      interval.appendChild(mcws.numberSpan(report, base + "/1"));
      interval.appendChild(document.createTextNode((answer.unit ? " " + answer.unit : "") + ")"));
      cell.appendChild(interval);
    }
    if (answer.note) cell.appendChild(mcws.element("div", {"class": "note"}, answer.note));
    container.appendChild(cell);
  });
};

mcws.renderTable = function (report, section, base, container) {
  const table = mcws.element("table");
  const head = mcws.element("tr");
  (section.columns || []).forEach(function (column) {
    head.appendChild(mcws.element("th", {}, mcws.withUnit(column.name, column.unit)));
  });
  table.appendChild(head);
  (section.rows || []).forEach(function (row, r) {
    const line = mcws.element("tr");
    row.forEach(function (cell, c) {
      if (typeof cell === "number") {
        const td = mcws.element("td", {"class": "number"});
        td.appendChild(mcws.numberSpan(report, base + "/rows/" + r + "/" + c));
        line.appendChild(td);
      } else {
        line.appendChild(mcws.element("td", {}, cell === null ? "n/a" : String(cell)));
      }
    });
    table.appendChild(line);
  });
  container.appendChild(table);
};

mcws.renderImage = function (section, container) {
  container.appendChild(mcws.element("img", {"class": "picture", "alt": section.alt || section.title || "",
                                             "src": "data:image/png;base64," + (section.png_base64 || "")}));
};

mcws.renderText = function (section, container) {
  container.appendChild(mcws.element("p", {"class": "text-section"}, section.text || ""));
};

// About `count` round tick values covering [low, high].
mcws.ticks = function (low, high, count) {
  if (!(high > low)) return [low];
  const raw = (high - low) / count;
  const power = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 2.5, 5, 10].map(function (f) { return f * power; })
                                 .find(function (s) { return s >= raw; });
  const ticks = [];
  for (let t = Math.ceil(low / step) * step; t <= high + step * 1e-9; t += step)
    ticks.push(Number(t.toPrecision(12)));
  return ticks;
};

mcws.range = function (numbers) {
  const finite = numbers.filter(function (v) { return typeof v === "number" && isFinite(v); });
  if (finite.length === 0) return [0, 1];
  let low = Math.min.apply(null, finite), high = Math.max.apply(null, finite);
  if (low === high) { low -= Math.abs(low) * 0.1 || 1; high += Math.abs(high) * 0.1 || 1; }
  return [low, high];
};

mcws.palette = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b"];

// Axes with ticks and labels "label [unit]"; returns the x and y scales of the plot area.
mcws.drawAxes = function (svg, box, xRange, yRange, xTitle, yTitle) {
  const sx = function (v) { return box.left + (v - xRange[0]) / (xRange[1] - xRange[0]) * box.width; };
  const sy = function (v) { return box.top + box.height - (v - yRange[0]) / (yRange[1] - yRange[0]) * box.height; };
  mcws.ticks(xRange[0], xRange[1], 6).forEach(function (t) {
    svg.appendChild(mcws.svgElement("line", {"class": "grid", x1: sx(t), x2: sx(t), y1: box.top, y2: box.top + box.height}));
    svg.appendChild(mcws.svgElement("text", {x: sx(t), y: box.top + box.height + 16, "text-anchor": "middle"}, mcws.formatNumber(t)));
  });
  if (yRange) {
    mcws.ticks(yRange[0], yRange[1], 5).forEach(function (t) {
      svg.appendChild(mcws.svgElement("line", {"class": "grid", x1: box.left, x2: box.left + box.width, y1: sy(t), y2: sy(t)}));
      svg.appendChild(mcws.svgElement("text", {x: box.left - 6, y: sy(t) + 4, "text-anchor": "end"}, mcws.formatNumber(t)));
    });
    svg.appendChild(mcws.svgElement("line", {"class": "axis", x1: box.left, x2: box.left, y1: box.top, y2: box.top + box.height}));
    svg.appendChild(mcws.svgElement("text", {x: 14, y: box.top + box.height / 2, "text-anchor": "middle",
                                             transform: "rotate(-90 14 " + (box.top + box.height / 2) + ")"}, yTitle));
  }
  svg.appendChild(mcws.svgElement("line", {"class": "axis", x1: box.left, x2: box.left + box.width,
                                           y1: box.top + box.height, y2: box.top + box.height}));
  svg.appendChild(mcws.svgElement("text", {x: box.left + box.width / 2, y: box.top + box.height + 36,
                                           "text-anchor": "middle"}, xTitle));
  return {x: sx, y: sy};
};

mcws.points = function (xs, ys, scale) {
  const out = [];
  for (let i = 0; i < Math.min(xs.length, ys.length); ++i)
    if (typeof xs[i] === "number" && typeof ys[i] === "number")
      out.push(scale.x(xs[i]).toFixed(2) + "," + scale.y(ys[i]).toFixed(2));
  return out;
};

mcws.renderChart = function (section, container) {
  const series = section.series || [];
  const all = function (key) { return [].concat.apply([], series.map(function (s) { return s[key] || []; })); };
  const x = section.x || {}, y = section.y || {};
  const box = {left: 70, top: 14, width: 560, height: 250};
  const svg = mcws.svgElement("svg", {width: 660, height: 320, "class": "chart", role: "img",
                                      "aria-label": section.title || "chart"});
  const scale = mcws.drawAxes(svg, box, mcws.range(all("x")), mcws.range(all("y").concat(all("lo"), all("hi"))),
                              mcws.withUnit(x.label || "x", x.unit), mcws.withUnit(y.label || "y", y.unit));
  series.forEach(function (s, i) {
    const colour = mcws.palette[i % mcws.palette.length];
    if (Array.isArray(s.lo) && Array.isArray(s.hi)) {
      const band = mcws.points(s.x, s.hi, scale).concat(mcws.points(s.x.slice().reverse(), s.lo.slice().reverse(), scale));
      svg.appendChild(mcws.svgElement("polygon", {points: band.join(" "), fill: colour, "fill-opacity": 0.18,
                                                  stroke: "none", "class": "band"}));
    }
    const line = mcws.points(s.x || [], s.y || [], scale);
    svg.appendChild(mcws.svgElement("polyline", {points: line.join(" "), fill: "none", stroke: colour, "stroke-width": 2}));
    line.forEach(function (p) {
      const xy = p.split(",");
      svg.appendChild(mcws.svgElement("circle", {cx: xy[0], cy: xy[1], r: 2.5, fill: colour}));
    });
    svg.appendChild(mcws.svgElement("rect", {x: box.left + box.width - 150, y: box.top + 6 + 16 * i, width: 12, height: 3, fill: colour}));
    svg.appendChild(mcws.svgElement("text", {x: box.left + box.width - 132, y: box.top + 11 + 16 * i}, s.name || ""));
  });
  container.appendChild(svg);
};

mcws.renderTimeline = function (section, container) {
  const lanes = section.lanes || [], events = section.events || [];
  const laneHeight = 26;
  const box = {left: 110, top: 8, width: 540, height: Math.max(1, lanes.length) * laneHeight};
  const svg = mcws.svgElement("svg", {width: 670, height: box.height + 56, "class": "timeline", role: "img",
                                      "aria-label": section.title || "timeline"});
  const times = [].concat.apply([], events.map(function (e) { return [e.start, e.end]; }));
  const scale = mcws.drawAxes(svg, box, mcws.range(times), null, mcws.withUnit("time", section.unit));
  lanes.forEach(function (lane, i) {
    svg.appendChild(mcws.svgElement("text", {x: box.left - 8, y: box.top + laneHeight * (i + 0.65),
                                             "text-anchor": "end"}, lane));
  });
  events.forEach(function (event) {
    const lane = lanes.indexOf(event.lane);
    if (lane < 0) return;
    const x0 = scale.x(event.start), x1 = scale.x(event.end);
    const bar = mcws.svgElement("rect", {x: x0, y: box.top + laneHeight * lane + 3, width: Math.max(1, x1 - x0),
                                         height: laneHeight - 6, fill: mcws.palette[lane % mcws.palette.length],
                                         "fill-opacity": 0.75});
    bar.appendChild(mcws.svgElement("title", {}, (event.label || "") + ": " + mcws.formatNumber(event.start) +
                                    " to " + mcws.formatNumber(event.end) + " " + (section.unit || "")));
    svg.appendChild(bar);
    svg.appendChild(mcws.svgElement("text", {x: x0 + 3, y: box.top + laneHeight * (lane + 0.65), "font-size": 10},
                                    event.label || ""));
  });
  container.appendChild(svg);
};

// The sections in their order, each under its title.
mcws.renderSections = function (report, sections, container) {
  sections.forEach(function (section, i) {
    const block = mcws.element("section", {"class": "section section-" + section.kind});
    block.appendChild(mcws.element("h2", {}, section.title || ""));
    const base = "/view/sections/" + i;
    if (section.kind === "table") mcws.renderTable(report, section, base, block);
    else if (section.kind === "image") mcws.renderImage(section, block);
    else if (section.kind === "chart") mcws.renderChart(section, block);
    else if (section.kind === "timeline") mcws.renderTimeline(section, block);
    else mcws.renderText(section, block);
    if (section.note) block.appendChild(mcws.element("p", {"class": "note"}, section.note));
    container.appendChild(block);
  });
};
