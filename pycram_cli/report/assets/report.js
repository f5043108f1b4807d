// pycram replay report: a 3D replay of a run (three.js), its plan tree and its timeline.
// Data: the JSON element #pycram-data, written by pycram_cli/report/page.py:
//   trace   the trace (plan, world, status, failure, params, root: the tree of nodes with timing)
//   scene   bodies -> links -> visual shapes (boxes, spheres, cylinders, capsules, meshes by index), meshes
//   frames  [0]: every drawn link's pose before the first step; [k]: after step k, only the links that moved;
//           each with the step's path and status and a camera [eye, target] on the robot and its work, and
//           `physics`: the frames physics made inside the step (simulated time t, the links moved since).
//   failures every failed step: its step, failure, the bodies it names, the target meant for them, a ghost of
//           the object there (its links' poses) and a camera on both.
// URL: #step=N (N may be a fraction: 11.5 is half-way through step 12) or #step=last opens the report at that
// step (a failed run opens at its failure); #failure=N at the N-th failed step; #node=PATH at a node (a
// composite: its first step), as clicking it in the tree does; #play starts playing; #select=NAME selects a body; #hide=A,B hides
// bodies; #png makes the image of the view (the link #png-link). window.pycramReport: seek(k), step(), select().
// `project` steps: DATA.projections (step path -> alternative -> run -> {root, status, failure, frames, failures})
// holds the projected runs the run kept the replay of; the step's table (in the header, and beside its steps)
// links each to #projected=PATH&alternative=NAME&run=N, which opens the page on that run alone, played like a run.
(function () {
  "use strict";
  const FULL = JSON.parse(document.getElementById("pycram-data").textContent);
  function projectedKey(hash) {  // #projected=PATH&alternative=NAME&run=N (each part URI-encoded) -> [path, name, run]
    const parts = {};
    for (const part of hash.replace(/^#/, "").split("&")) {
      const at = part.indexOf("=");
      if (at > 0) parts[part.slice(0, at)] = decodeURIComponent(part.slice(at + 1));
    }
    return parts.projected === undefined ? null : [parts.projected, parts.alternative || "", parts.run || ""];
  }
  const opened = projectedKey(location.hash);
  const kept = opened ? ((((FULL.projections || {})[opened[0]] || {})[opened[1]] || {})[opened[2]] || null) : null;
  const DATA = kept ? { ...FULL, frames: kept.frames, failures: kept.failures,
    trace: { ...FULL.trace, status: kept.status, failure: kept.failure, root: kept.root } } : FULL;
  // opening another projected run, or going back to the run, makes the page again
  window.addEventListener("hashchange", () => {
    if (JSON.stringify(projectedKey(location.hash)) !== JSON.stringify(kept ? opened : null)) location.reload();
  });
  function projectedLink(path, name, run) {
    return `#projected=${encodeURIComponent(path)}&alternative=${encodeURIComponent(name)}&run=${encodeURIComponent(run)}`;
  }
  const trace = DATA.trace, scene = DATA.scene, frames = DATA.frames;
  const STEPS = frames.length - 1;
  const $ = (id) => document.getElementById(id);
  const ICON = { succeeded: "✓", failed: "✗", recovered: "↺", cancelled: "⊘", skipped: "·", running: "▶", pending: "○" };

  // ---------------------------------------------------------------- the plan tree as a model
  const nodes = [];
  const byPath = new Map();
  function index(data, parent, depth) {
    const node = { data, parent, depth, children: [], first: Infinity, last: -1, li: null, row: -1 };
    nodes.push(node);
    byPath.set(data.path, node);
    for (const child of data.children || []) node.children.push(index(child, node, depth + 1));
    return node;
  }
  const root = index(trace.root || { path: "body", type: "seq", status: trace.status }, null, 0);
  // a failure is recovered when something above it (a retry, a catch, try_all...) still succeeded
  for (const node of nodes) {
    let up = node.parent, recovered = false;
    while (up && !recovered) { recovered = up.data.status === "succeeded"; up = up.parent; }
    node.final = node.data.status === "failed" && recovered ? "recovered" : node.data.status;
  }
  // the steps (frames) below every node, and the time each step ended
  const frameTime = [0];
  frames.forEach((frame, k) => {
    if (k === 0) return;
    const node = byPath.get(frame.path);
    for (let up = node; up; up = up.parent) { up.first = Math.min(up.first, k); up.last = Math.max(up.last, k); }
    const t = node && node.data.timing;
    frameTime.push(t && t.started != null ? t.started + (t.duration || 0) : frameTime[k - 1]);
  });
  const timed = (n) => n.data.timing && n.data.timing.started != null;
  const endOf = (n) => n.data.timing.started + (n.data.timing.duration || 0);
  const totalTime = Math.max(1e-6, (trace.timing && trace.timing.duration) || (timed(root) ? endOf(root) : 0),
    ...nodes.filter(timed).map(endOf));

  function stateAt(node, k) {
    if (k >= STEPS) return node.final;
    if (node.last >= 0) return node.last <= k ? node.final : node.first <= k ? "running" : "pending";
    if (timed(node) && k > 0) {
      const now = frameTime[k];
      return endOf(node) <= now ? node.final : node.data.timing.started <= now ? "running" : "pending";
    }
    if (!node.parent) return "pending";
    const above = stateAt(node.parent, k);
    return above === "running" || above === "pending" ? "pending" : node.final;
  }

  // ---------------------------------------------------------------- words for nodes (as `pycram trace show`)
  function short(value, limit) {
    limit = limit || 70;
    const text = typeof value === "string" ? value : JSON.stringify(value);
    return text === undefined ? "" : text.length <= limit ? text : text.slice(0, limit - 1) + "…";
  }
  const slots = (values) => Object.entries(values || {}).map(([k, v]) => `${k}=${short(v, 40)}`).join(", ");
  function condition(record) {
    const verdict = (record.holds !== undefined ? record.holds : record.value) ? "holds" : "does not hold";
    if (record.query) return `${record.query.name}(${slots(record.query.args)}) → ${short(record.query.result)}: ${verdict}`;
    if (record.variable !== undefined) return `${record.variable} = ${short(record.value, 50)}: ${verdict}`;
    if (record.not) return `not (${condition(record.not)})`;
    if (record.equal) return `${short(record.equal[0], 30)} = ${short(record.equal[1], 30)}: ${verdict}`;
    return verdict;
  }
  function describe(data) {
    const parts = [];
    if (data.designator) parts.push(slots(data.designator.resolved || data.designator.slots));
    if (data.query) parts.push(`${slots(data.query.args)} → ${short(data.query.result)}`);
    if (data.condition) parts.push(condition(data.condition));
    if (data.call) parts.push(slots(data.call.args));
    if (data.item !== undefined) parts.push(`= ${short(data.item)}`);
    if (data.message !== undefined) parts.push(`“${data.message}”`);
    if (data.caught) parts.push(`caught ${data.caught.type}`);
    if (data.retries) parts.push(`${data.retries} retr${data.retries === 1 ? "y" : "ies"}`);
    if (data.bound) parts.push(Object.entries(data.bound).map(([k, v]) => `$${k} = ${short(v, 50)}`).join("; "));
    const failure = data.failure;
    if (failure && data.status === "failed" && failure.path === data.path) parts.push(`${failure.type}: ${failure.message}`);
    return parts.filter(Boolean).join("  ");
  }
  const label = (data) => String(data.path || "?").split("/").pop();
  const seconds = (data) => data.timing && data.timing.duration != null ? `${data.timing.duration.toFixed(2)} s` : "";
  function el(tag, attrs, ...children) {
    const element = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === "class") element.className = v; else if (k === "text") element.textContent = v; else element.setAttribute(k, v);
    }
    for (const child of children) if (child != null) element.append(child);
    return element;
  }

  // ---------------------------------------------------------------- header
  (function header() {
    const h = $("header");
    h.append(el("h1", { text: `${trace.plan || "plan"} on ${trace.world || DATA.world_file}` }),
      el("span", { class: `badge ${trace.status}`, text: trace.status || "?" }),
      el("span", { class: "meta", text: `${STEPS} steps · ${totalTime.toFixed(2)} s` }));
    const params = Object.entries(trace.params || {});
    if (params.length) h.append(el("span", { class: "meta", text: params.map(([k, v]) => `${k}=${short(v, 40)}`).join(", ") }));
    h.append(el("span", { class: "meta", text: DATA.generator || "" }));
    if (trace.failure) {
      h.append(el("div", { class: "failure", text: `${trace.failure.type} at ${trace.failure.path}: ${trace.failure.message}` }));
    }
    if (kept) {
      h.append(el("div", { class: "projected", id: "projected-banner" },
        `Projected run ${opened[2]} of “${opened[1]}” at ${opened[0]}: tried in prospection before the robot acted — the world did not do this. `,
        el("a", { href: "#", id: "back-to-run", text: "back to the run" })));
    }
    for (const node of nodes) {
      if (!kept && node.data.projection) {
        const p = node.data.projection;
        h.append(el("details", { class: "projection" }, el("summary", { text: `projected at ${node.data.path}: ${p.choice === null ? "nothing good enough" : `chose ${p.choice}`} (${p.why})` }),
          projectionTable(node.data)));
      }
    }
  })();

  // ---------------------------------------------------------------- a `project` step's table of projected runs
  function projectionTable(data) {
    const p = data.projection, keptRuns = (FULL.projections || {})[data.path] || {};
    const table = el("table", { class: "projection-table", "data-step": data.path });
    table.append(el("tr", {}, el("th", { text: "alternative" }), el("th", { text: "succeeded" }), el("th", { text: "failures" }),
      el("th", { text: "runs (click one with a replay to open it)" })));
    for (const [name, row] of Object.entries(p.alternatives || {})) {
      const runs = el("td", { class: "runs" });
      for (const outcome of row.outcomes || []) {
        const mark = { succeeded: "✓", failed: "✗", error: "!", timeout: "⏱", impossible: "·" }[outcome.status] || "?";
        const title = `run ${outcome.run}: ${outcome.status}${outcome.failure ? ` — ${outcome.failure}` : ""}`;
        const replayed = keptRuns[name] && keptRuns[name][String(outcome.run)];
        runs.append(replayed
          ? el("a", { class: `run st-${outcome.status}`, href: projectedLink(data.path, name, String(outcome.run)), title: `${title} (open its replay)`, text: mark })
          : el("span", { class: `run st-${outcome.status}`, title, text: mark }));
      }
      const causes = Object.entries(row.failures || {}).map(([kind, count]) => `${count} ${kind}`).join(", ");
      table.append(el("tr", { class: name === p.choice ? "chosen" : "" }, el("td", { text: name + (name === p.choice ? " (chosen)" : "") }),
        el("td", { text: `${row.succeeded} of ${row.runs}` }), el("td", { text: causes || "—" }), runs));
    }
    return table;
  }

  // ---------------------------------------------------------------- the tree
  function buildTree(node) {
    const data = node.data;
    const info = describe(data);
    const answer = data.query || (data.condition && data.condition.query);
    const row = el("div", { class: "row", title: data.path },
      el("span", { class: "fold", text: node.children.length ? "▾" : "" }),
      el("span", { class: "icon", text: ICON[node.final] || "?" }),
      el("span", { class: "label", text: label(data) }),
      info ? el("span", { class: answer ? "info answer" : "info", text: info }) : null,
      el("span", { class: "dur", text: seconds(data) }));
    const li = el("li", { class: `st-${node.final}`, "data-path": data.path }, row);
    node.li = li;
    row.addEventListener("click", (event) => {
      if (event.target.classList.contains("fold")) { li.classList.toggle("folded"); event.target.textContent = li.classList.contains("folded") ? "▸" : "▾"; return; }
      seek(stepOf(node));
    });
    if (node.children.length) li.append(el("ul", {}, ...node.children.map(buildTree)));
    return li;
  }
  $("tree").append(el("ul", {}, buildTree(root)));

  function stepOf(node) {  // a step: its own frame; a composite: its first step's
    if (node.last >= 0) return node.children.length ? node.first : node.last;
    if (timed(node)) { let k = 0; while (k < STEPS && frameTime[k + 1] <= node.data.timing.started) k++; return k; }
    return node.parent ? stepOf(node.parent) : 0;
  }

  // ---------------------------------------------------------------- the timeline (Gantt)
  const ROW = 16;
  let LABELS = 250;  // the width of the row names: less in a narrow window
  const rows = nodes.filter(timed);
  rows.forEach((node, i) => { node.row = i; });
  const svgNS = "http://www.w3.org/2000/svg";
  function svg(tag, attrs, text) {
    const element = document.createElementNS(svgNS, tag);
    for (const [k, v] of Object.entries(attrs || {})) element.setAttribute(k, v);
    if (text !== undefined) element.textContent = text;
    return element;
  }
  let timeline = null, cursor = null, currentRow = null, xOf = () => 0;
  function buildTimeline() {
    const box = $("timeline");
    box.textContent = "";
    const width = Math.max(480, box.clientWidth - 18), height = rows.length * ROW + 24;  // room for a scroll bar
    LABELS = width < 900 ? 170 : 250;
    const span = width - LABELS - 16;
    xOf = (t) => LABELS + (t / totalTime) * span;
    timeline = svg("svg", { width, height });
    currentRow = svg("rect", { class: "current-row", x: 0, y: 0, width, height: ROW, visibility: "hidden" });
    timeline.append(currentRow);
    for (let i = 0; i <= 5; i++) {
      const x = xOf((totalTime * i) / 5);
      timeline.append(svg("line", { class: "grid", x1: x, x2: x, y1: 0, y2: height }));
      timeline.append(svg("text", { class: "axis", x: x + 2, y: height - 6 }, `${((totalTime * i) / 5).toFixed(2)} s`));
    }
    // branches that run side by side: one shaded band per concurrent composite, over its children's rows
    for (const node of rows) {
      if (!["par", "pursue", "try_all"].includes(node.data.type) || !node.children.length) continue;
      const inside = rows.filter((r) => r !== node && r.data.path.startsWith(node.data.path + "/"));
      if (!inside.length) continue;
      const top = Math.min(...inside.map((r) => r.row)), bottom = Math.max(...inside.map((r) => r.row));
      timeline.append(svg("rect", { class: "band", x: 0, y: top * ROW, width, height: (bottom - top + 1) * ROW }));
    }
    const colour = { succeeded: "#51cf66", failed: "#ff6b6b", recovered: "#ffa94d", cancelled: "#adb5bd", skipped: "#dee2e6" };
    for (const node of rows) {
      const y = node.row * ROW;
      const text = svg("text", { class: "lbl", x: 4 + node.depth * 9, y: y + 12 }, label(node.data));
      text.append(svg("title", {}, node.data.path));
      const start = node.data.timing.started, end = endOf(node);
      const bar = svg("rect", { class: "bar", x: xOf(start), y: y + 3, width: Math.max(2, xOf(end) - xOf(start)), height: ROW - 6,
        rx: 2, fill: colour[node.final] || "#74c0fc" });
      bar.append(svg("title", {}, `${node.data.path}\n${node.final}, ${seconds(node.data) || "0 s"} from ${start.toFixed(3)} s`));
      for (const element of [text, bar]) element.addEventListener("click", () => seek(stepOf(node)));
      timeline.append(text, bar);
    }
    cursor = svg("line", { class: "cursor", x1: LABELS, x2: LABELS, y1: 0, y2: height - 18 });
    timeline.append(cursor);
    box.append(timeline);
  }
  buildTimeline();

  // ---------------------------------------------------------------- the 3D view
  const view = $("view");
  let renderer = null;
  try {
    const canvas = document.createElement("canvas");
    const context = canvas.getContext("webgl2", { preserveDrawingBuffer: true, antialias: true }) ||
      canvas.getContext("webgl", { preserveDrawingBuffer: true, antialias: true });
    if (context) renderer = new THREE.WebGLRenderer({ canvas, context, antialias: true, preserveDrawingBuffer: true });
  } catch (error) {
    renderer = null;
  }
  document.body.dataset.webgl = renderer ? "ok" : "unavailable";
  const notices = [];
  if (!renderer) notices.push("This browser cannot draw 3D here (WebGL is off or unavailable): the plan tree, the step details and the timeline still work.");
  if (!DATA.replayed) notices.push("This trace has no replay record, so the 3D view shows the world as it was loaded (record one with pycram run --trace).");
  if ((scene.skipped || []).length) notices.push(`Not drawn (unsupported shapes): ${scene.skipped.slice(0, 6).join(", ")}${scene.skipped.length > 6 ? ", …" : ""}`);
  if (notices.length) { $("notice").hidden = false; $("notice").textContent = notices.join(" "); }

  THREE.Object3D.DEFAULT_UP.set(0, 0, 1);
  const world = new THREE.Scene();
  world.background = new THREE.Color(0xdde3ea);
  const camera = new THREE.PerspectiveCamera(50, 1.6, 0.05, 100);
  camera.up.set(0, 0, 1);
  world.add(new THREE.HemisphereLight(0xffffff, 0x8a8f99, 1.9));
  const sun = new THREE.DirectionalLight(0xffffff, 1.4);
  sun.position.set(-3, -2, 6);
  world.add(sun);
  const fill = new THREE.DirectionalLight(0xffffff, 0.5);
  fill.position.set(4, 3, 2);
  world.add(fill);

  function bytes(text) {
    const raw = atob(text), out = new Uint8Array(raw.length);
    for (let i = 0; i < raw.length; i++) out[i] = raw.charCodeAt(i);
    return out.buffer;
  }
  const meshGeometry = (scene.meshes || []).map((mesh) => {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(bytes(mesh.positions)), 3));
    const indices = mesh.index_bytes === 4 ? new Uint32Array(bytes(mesh.indices)) : new Uint16Array(bytes(mesh.indices));
    geometry.setIndex(new THREE.BufferAttribute(indices, 1));
    return THREE.toCreasedNormals(geometry, Math.PI / 6);
  });
  const geometries = new Map(), materials = new Map();
  function cached(map, key, make) { if (!map.has(key)) map.set(key, make()); return map.get(key); }
  function tinted(store, material, colour, intensity, finish = () => {}) {  // a material's glowing copy, made once
    return cached(store, material.uuid, () => {
      const copy = material.clone();
      copy.emissive = new THREE.Color(colour);
      copy.emissiveIntensity = intensity;
      finish(copy);
      return copy;
    });
  }
  function geometryOf(shape) {
    switch (shape.kind) {
      case "box": return cached(geometries, `b${shape.size}`, () => new THREE.BoxGeometry(...shape.size));
      case "sphere": return cached(geometries, `s${shape.radius}`, () => new THREE.SphereGeometry(shape.radius, 24, 16));
      case "cylinder": return cached(geometries, `c${shape.radius},${shape.length}`,
        () => new THREE.CylinderGeometry(shape.radius, shape.radius, shape.length, 28).rotateX(Math.PI / 2));
      case "capsule": return cached(geometries, `p${shape.radius},${shape.length}`,
        () => new THREE.CapsuleGeometry(shape.radius, shape.length, 8, 20).rotateX(Math.PI / 2));
      case "mesh": return meshGeometry[shape.mesh];
      default: return null;
    }
  }
  function materialOf(rgba) {
    return cached(materials, rgba.join(","), () => {
      const material = new THREE.MeshLambertMaterial({ side: THREE.DoubleSide });
      material.color.setRGB(rgba[0], rgba[1], rgba[2], THREE.SRGBColorSpace);
      if (rgba[3] < 1) { material.transparent = true; material.opacity = rgba[3]; }
      return material;
    });
  }
  const links = [];     // every drawn link (a Group), in the order of the frames' (body, slot) pairs
  const offset = [];    // body index -> index of its first link in `links`
  let robotLink = -1;
  const bodyLinks = [];  // body index -> its drawn links (Groups)
  (scene.bodies || []).forEach((body, b) => {
    offset.push(links.length);
    bodyLinks.push([]);
    body.links.forEach((link, slot) => {
      const group = new THREE.Group();
      group.name = `${body.name}/${link.name}`;
      for (const shape of link.shapes) {
        const geometry = geometryOf(shape);
        if (!geometry) continue;
        const mesh = new THREE.Mesh(geometry, materialOf(shape.color));
        const o = shape.origin;
        mesh.position.set(o[0], o[1], o[2]);
        mesh.quaternion.set(o[3], o[4], o[5], o[6]);
        if (shape.scale) mesh.scale.set(...shape.scale);
        mesh.userData.body = b;
        mesh.userData.base = mesh.material;
        group.add(mesh);
      }
      group.matrixAutoUpdate = true;
      group.userData.body = b;
      bodyLinks[b].push(group);
      world.add(group);
      if (body.type === "robot" && robotLink < 0) robotLink = links.length;
      links.push(group);
    });
  });

  // every frame's full pose list (frames only carry what moved)
  const L = links.length;
  const full = [], physicsFull = [];  // physicsFull[k]: the full pose list after each physics frame of step k
  function put(poses, flat) {
    for (let i = 0; i + 9 <= flat.length; i += 9) {
      const at = (offset[flat[i]] + flat[i + 1]) * 7;
      for (let j = 0; j < 7; j++) poses[at + j] = flat[i + 2 + j];
    }
    return poses;
  }
  frames.forEach((frame, k) => {
    let poses = k === 0 ? new Float32Array(L * 7) : full[k - 1];
    physicsFull.push(k > 0 && frame.physics && frame.physics.length ?
      frame.physics.map((sub) => (poses = put(poses.slice(), sub.poses || []))) : null);
    full.push(put(poses.slice(), frame.poses || []));
  });
  const KINEMATIC = 0.3;  // the share of a step with physics that shows what happened before physics ran
  const qa = new THREE.Quaternion(), qb = new THREE.Quaternion();
  const ease = (a) => a * a * (3 - 2 * a);
  function pose(t) {
    const k = Math.max(0, Math.min(STEPS, Math.floor(t)));
    const a = k >= STEPS ? 0 : t - k;
    const next = Math.min(STEPS, k + 1), subs = physicsFull[next];
    let from = full[k], to = full[next], s = ease(a);
    if (a > 0 && subs) {  // through the physics frames: eased to the first, then at an even pace
      const keys = [...subs, full[next]];
      if (a < KINEMATIC) { to = keys[0]; s = ease(a / KINEMATIC); }
      else {
        const u = ((a - KINEMATIC) / (1 - KINEMATIC)) * (keys.length - 1), i = Math.min(keys.length - 2, Math.floor(u));
        from = keys[i]; to = keys[i + 1]; s = u - i;
      }
    }
    for (let i = 0; i < L; i++) {
      const p = i * 7, group = links[i];
      if (s === 0 || from === to) {
        group.position.set(from[p], from[p + 1], from[p + 2]);
        group.quaternion.set(from[p + 3], from[p + 4], from[p + 5], from[p + 6]);
      } else {
        group.position.set(from[p] + (to[p] - from[p]) * s, from[p + 1] + (to[p + 1] - from[p + 1]) * s,
          from[p + 2] + (to[p + 2] - from[p + 2]) * s);
        qa.set(from[p + 3], from[p + 4], from[p + 5], from[p + 6]);
        qb.set(to[p + 3], to[p + 4], to[p + 5], to[p + 6]);
        group.quaternion.copy(qa.slerp(qb, s));
      }
    }
    showWhatif(t);
    if (follow.checked) {
      const c0 = frames[k].camera, c1 = frames[next].camera, e = ease(a);
      if (c0) {
        const c = c1 && e > 0 ? c0.map((v, i) => v + (c1[i] - v) * e) : c0;
        camera.position.set(c[0], c[1], c[2]);
        if (controls) { controls.target.set(c[3], c[4], c[5]); controls.update(); } else camera.lookAt(c[3], c[4], c[5]);
      }
    }
  }

  const follow = $("follow");
  let controls = null;
  if (renderer) {
    renderer.setPixelRatio(Math.min(2, window.devicePixelRatio || 1));
    view.prepend(renderer.domElement);
    controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.enableDamping = false;
    controls.addEventListener("start", () => { follow.checked = false; });
    controls.addEventListener("change", () => { dirty = true; });
  }
  follow.addEventListener("change", () => { pose(position); dirty = true; });
  function resize() {
    const width = Math.max(1, view.clientWidth), height = Math.max(1, view.clientHeight);
    camera.aspect = width / height;
    camera.updateProjectionMatrix();
    if (renderer) renderer.setSize(width, height, false);
    const rect = view.getBoundingClientRect();
    document.body.dataset.view = [rect.left, rect.top, rect.width, rect.height].map(Math.round).join(",");
    // whether the layout fits the window: nothing wider than it, the controls on screen, a view to see
    const controlsBox = $("controls").getBoundingClientRect();
    document.body.dataset.fits = String(document.documentElement.scrollWidth <= window.innerWidth + 1 &&
      controlsBox.right <= window.innerWidth + 1 && controlsBox.bottom <= window.innerHeight + 1 && rect.height >= 200);
    dirty = true;
  }
  window.addEventListener("resize", () => { resize(); buildTimeline(); showStep(shown, true); });


  // ---------------------------------------------------------------- bodies: labels, selection, hiding
  const bodies = scene.bodies || [];
  const bodyIndex = new Map(bodies.map((body, b) => [body.name, b]));
  const hidden = new Set();
  let selected = -1;
  const labelBox = el("div", { id: "labels" });
  view.append(labelBox);
  const labels = bodies.map((body, b) => {
    if (body.type === "environment" || !bodyLinks[b].length) return null;
    const tag = el("span", { class: "label3d", text: body.name, "data-body": body.name });
    tag.addEventListener("click", () => select(b));
    labelBox.append(tag);
    return tag;
  });
  const box3 = new THREE.Box3(), v3 = new THREE.Vector3();
  function placeLabels() {
    const width = view.clientWidth, height = view.clientHeight;
    const show = $("show-labels").checked;
    labels.forEach((tag, b) => {
      if (!tag) return;
      if (!show || hidden.has(b)) { tag.hidden = true; return; }
      box3.makeEmpty();
      for (const group of bodyLinks[b]) box3.expandByObject(group);
      if (box3.isEmpty()) { tag.hidden = true; return; }
      box3.getCenter(v3);
      v3.z = box3.max.z + 0.03;
      v3.project(camera);
      const inside = v3.z < 1 && Math.abs(v3.x) <= 1 && Math.abs(v3.y) <= 1;
      tag.hidden = !inside;
      if (inside) tag.style.transform = `translate(${((v3.x + 1) / 2) * width}px, ${((1 - v3.y) / 2) * height}px) translate(-50%, calc(-100% - 14px))`;
      tag.classList.toggle("selected", b === selected);
    });
  }
  function setHidden(b, hide) {
    if (hide) hidden.add(b); else hidden.delete(b);
    for (const group of bodyLinks[b]) group.visible = !hide;
    const box = document.querySelector(`#bodies-menu input[data-body="${CSS.escape(bodies[b].name)}"]`);
    if (box) box.checked = !hide;
    document.body.dataset.hidden = [...hidden].map((i) => bodies[i].name).sort().join(",");
    dirty = true;
  }
  const menu = $("bodies-list");
  bodies.forEach((body, b) => {
    if (!bodyLinks[b].length) return;
    const box = el("input", { type: "checkbox", "data-body": body.name });
    box.checked = true;
    box.addEventListener("change", () => setHidden(b, !box.checked));
    menu.append(el("label", {}, box, ` ${body.name}`, el("span", { class: "hint", text: ` ${body.type}` })));
  });
  $("show-labels").addEventListener("change", () => { dirty = true; });

  function bodyPose(b) {  // the body's base link (its first drawn link): position and tilt from upright
    const group = bodyLinks[b][0], q = group.quaternion;
    const tilt = Math.acos(Math.max(-1, Math.min(1, 1 - 2 * (q.x * q.x + q.y * q.y)))) * 180 / Math.PI;
    const yaw = Math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z)) * 180 / Math.PI;
    return { position: [group.position.x, group.position.y, group.position.z], tilt, yaw };
  }
  function select(b) {
    selected = b;
    document.body.dataset.selected = b >= 0 ? bodies[b].name : "";
    repaint();
    details(shown);
  }
  const raycaster = new THREE.Raycaster(), pointer = new THREE.Vector2();
  let pressed = null;
  view.addEventListener("pointerdown", (event) => { pressed = [event.clientX, event.clientY]; });
  view.addEventListener("pointerup", (event) => {
    if (!pressed || Math.hypot(event.clientX - pressed[0], event.clientY - pressed[1]) > 4 || !renderer) return;
    const rect = renderer.domElement.getBoundingClientRect();
    pointer.set(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(pointer, camera);
    const hit = raycaster.intersectObjects(links.filter((g) => g.visible), true)
      .find((h) => h.object.userData.body !== undefined && h.object.visible);
    select(hit ? hit.object.userData.body : -1);
  });

  // ---------------------------------------------------------------- failures: highlighted, with the target's ghost
  const failures = (DATA.failures || []).filter((f) => byPath.has(f.path)).sort((a, b) => a.step - b.step);
  for (const failure of failures) failure.fatal = byPath.get(failure.path).final !== "recovered";
  const glow = new Map();
  function glowing(material) {
    return tinted(glow, material, 0xd6336c, 0.55, (copy) => {
      copy.depthTest = false;  // seen through whatever hides it (a drawer, the robot)
      copy.transparent = true;
      copy.opacity = Math.min(copy.opacity, 0.9);
    });
  }
  const ghostMaterial = new THREE.MeshLambertMaterial({ color: 0x2f9e44, transparent: true, opacity: 0.38, depthWrite: false });
  const markerMaterial = new THREE.MeshBasicMaterial({ color: 0x2f9e44, transparent: true, opacity: 0.8, side: THREE.DoubleSide });
  for (const failure of failures) {  // the ghost: the object's shapes at the poses meant for it, and a ring at the target
    const ghost = new THREE.Group();
    if (failure.ghost && bodies[failure.ghost.body]) {
      const flat = failure.ghost.poses;
      for (let i = 0; i + 9 <= flat.length; i += 9) {
        const source = bodyLinks[flat[i]][flat[i + 1]];
        if (!source) continue;
        const link = new THREE.Group();
        link.position.set(flat[i + 2], flat[i + 3], flat[i + 4]);
        link.quaternion.set(flat[i + 5], flat[i + 6], flat[i + 7], flat[i + 8]);
        for (const mesh of source.children) {
          const copy = new THREE.Mesh(mesh.geometry, ghostMaterial);
          copy.position.copy(mesh.position); copy.quaternion.copy(mesh.quaternion); copy.scale.copy(mesh.scale);
          copy.renderOrder = 2;
          link.add(copy);
        }
        ghost.add(link);
      }
    }
    if (failure.target) {
      const ring = new THREE.Mesh(new THREE.RingGeometry(0.035, 0.05, 32), markerMaterial);
      ring.position.set(failure.target[0], failure.target[1], failure.target[2] + 0.002);
      ghost.add(ring);
    }
    ghost.visible = false;
    world.add(ghost);
    failure.drawn = ghost;
  }
  const faded = new Map();
  function fading(material) {  // robots see-through while a failure is shown: they must not hide what failed
    return cached(faded, material.uuid, () => {
      const copy = material.clone();
      copy.transparent = true;
      copy.opacity = Math.min(copy.opacity, 0.25);
      copy.depthWrite = false;
      return copy;
    });
  }
  const robots = bodies.map((body, b) => (body.type === "robot" ? b : -1)).filter((b) => b >= 0);
  function paint(list, make) {
    for (const b of list) for (const group of bodyLinks[b] || []) for (const mesh of group.children) mesh.material = make(mesh.userData.base);
  }
  // what a query simulated on the prospection copy (stable): an amber ghost of the object moving through it
  const whatifMaterial = new THREE.MeshLambertMaterial({ color: 0xf08c00, transparent: true, opacity: 0.45, depthWrite: false });
  const whatifGhosts = new Map();  // step -> [link Groups of the ghost]
  function whatifGhost(k) {
    const info = frames[k] && frames[k].whatif;
    if (!info || !bodyLinks[info.body]) return null;
    if (!whatifGhosts.has(k)) {
      const parts = bodyLinks[info.body].map((source) => {
        const link = new THREE.Group();
        for (const mesh of source.children) {
          const copy = new THREE.Mesh(mesh.geometry, whatifMaterial);
          copy.position.copy(mesh.position); copy.quaternion.copy(mesh.quaternion); copy.scale.copy(mesh.scale);
          copy.renderOrder = 2;
          link.add(copy);
        }
        link.visible = false;
        world.add(link);
        return link;
      });
      whatifGhosts.set(k, parts);
    }
    return whatifGhosts.get(k);
  }
  let whatifShown = null;
  function showWhatif(t) {  // at t in (k-1, k]: the ghost at the simulation's frame for the step's progress
    const k = Math.max(1, Math.min(STEPS, Math.ceil(t - 1e-6)));
    const parts = t > 0 ? whatifGhost(k) : null;
    if (whatifShown && whatifShown !== parts) for (const link of whatifShown) link.visible = false;
    whatifShown = parts;
    document.body.dataset.whatif = parts ? bodies[frames[k].whatif.body].name : "";
    if (!parts) return;
    const list = frames[k].whatif.frames, a = t - (k - 1);
    const flat = list[Math.min(list.length - 1, Math.floor(a * list.length))].poses;
    for (let i = 0; i + 9 <= flat.length; i += 9) {
      const link = parts[flat[i + 1]];
      if (!link) continue;
      link.position.set(flat[i + 2], flat[i + 3], flat[i + 4]);
      link.quaternion.set(flat[i + 5], flat[i + 6], flat[i + 7], flat[i + 8]);
      link.visible = true;
    }
  }
  let activeFailure = null, painted = [], reasoningBodies = [];
  const selectedMaterial = new Map();
  function selecting(material) { return tinted(selectedMaterial, material, 0xfab005, 0.45); }
  function repaint() {  // every highlight from scratch: a failure's, the reasoning's, the selection
    paint(painted, (base) => base);
    painted = [];
    const apply = (list, make) => { paint(list, make); painted.push(...list); };
    const failed = activeFailure ? activeFailure.objects : [];
    if (activeFailure && (failed.length || activeFailure.target)) apply(robots.filter((b) => !failed.includes(b)), fading);
    apply(reasoningBodies, glowingOrange);
    if (selected >= 0 && !failed.includes(selected)) apply([selected], selecting);
    apply(failed, glowing);
    dirty = true;
  }
  function showFailure(k) {
    const failure = failures.find((f) => f.step === k) || null;
    if (failure === activeFailure) return;
    if (activeFailure) activeFailure.drawn.visible = false;
    activeFailure = failure;
    repaint();
    const box = $("failbox");
    box.hidden = !failure;
    document.body.dataset.failure = failure ? String(failure.step) : "";
    document.body.dataset.highlighted = failure ? failure.objects.map((b) => bodies[b].name).join(",") : "";
    document.body.dataset.ghost = failure && failure.ghost ? bodies[failure.ghost.body].name : "";
    if (!failure) return;
    failure.drawn.visible = true;
    for (const b of failure.objects) for (const group of bodyLinks[b] || []) for (const mesh of group.children) mesh.renderOrder = 5;
    box.textContent = "";
    const names = failure.objects.map((b) => bodies[b].name);
    box.append(el("div", {}, el("span", { class: `tag ${failure.fatal ? "fatal" : "recovered"}`, text: failure.fatal ? "✗ failed" : "↺ recovered" }),
      " ", el("b", { text: `${failure.type || "failure"}` }), ` at ${label(byPath.get(failure.path).data)}`),
      el("div", { class: "message", text: failure.message || "" }));
    if (names.length || failure.target) {
      box.append(el("div", { class: "legend" },
        names.length ? el("span", { class: "swatch object" }) : null, names.length ? ` ${names.join(", ")}  ` : "",
        failure.target ? el("span", { class: "swatch ghost" }) : null,
        failure.target ? ` where it was meant to go [${failure.target.map((v) => v.toFixed(2)).join(", ")}]` : ""));
    }
  }
  document.body.dataset.failures = String(failures.length);
  const nextFailure = $("next-failure");
  if (failures.length) {
    nextFailure.hidden = false;
    nextFailure.title = `Next failure (f): ${failures.length} failed step${failures.length === 1 ? "" : "s"}, recovered ones too`;
  }
  function goToNextFailure() {
    if (!failures.length) return;
    const target = failures.find((f) => f.step > shown) || failures[0];
    follow.checked = true;
    seek(target.step);
  }
  nextFailure.addEventListener("click", goToNextFailure);


  // ---------------------------------------------------------------- reasoning drawn in 3D: view cones, candidate maps, reach
  const OUTCOME_COLOURS = { "ok": 0x1ea03c, "collides": 0xdc3c32, "occupied": 0xdc3c32, "out of reach": 0xfabe78,
    "out of view": 0xc8aae6, "cannot hold": 0x96643c, "blocked": 0xc828c8, "not visible": 0x3c6ee6, "unstable": 0xf09614,
    "not tried": 0xcdcdcd };
  const reasoning = new THREE.Group();
  world.add(reasoning);
  const lineMaterial = (colour) => new THREE.LineBasicMaterial({ color: colour, transparent: true, opacity: 0.9, depthTest: false });
  function lines(points, colour) {  // points: [[a, b], ...] pairs of [x, y, z]
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.Float32BufferAttribute(points.flat(2), 3));
    const segments = new THREE.LineSegments(geometry, lineMaterial(colour));
    segments.renderOrder = 3;
    return segments;
  }
  function viewCone(view) {  // the camera's frustum, from its optical frame (axes: right, down, forward)
    const a = view.axes, eye = view.eye, L = view.length;
    const tx = Math.tan(view.fov[0] / 2) * L, ty = Math.tan(view.fov[1] / 2) * L;
    const at = (sx, sy) => [0, 1, 2].map((i) => eye[i] + a[6 + i] * L + a[i] * sx * tx + a[3 + i] * sy * ty);
    const c = [at(-1, -1), at(1, -1), at(1, 1), at(-1, 1)];
    const pairs = c.map((p) => [eye, p]).concat(c.map((p, i) => [p, c[(i + 1) % 4]]));
    const group = new THREE.Group();
    group.add(lines(pairs, view.occluders.length ? 0xe8590c : 0x1971c2));
    const face = new THREE.BufferGeometry();
    face.setAttribute("position", new THREE.Float32BufferAttribute([eye, c[0], c[1], eye, c[1], c[2], eye, c[2], c[3], eye, c[3], c[0]].flat(), 3));
    group.add(new THREE.Mesh(face, new THREE.MeshBasicMaterial({ color: 0x74c0fc, transparent: true, opacity: 0.12, side: THREE.DoubleSide, depthWrite: false })));
    if (view.target) group.add(lines([[eye, view.target]], 0x1971c2));
    return group;
  }
  function bytesOf(text) { return new Uint8Array(bytes(text)); }
  function candidateMap(map) {  // one square per candidate position, coloured by the test that ruled it out
    const group = new THREE.Group();
    const xy = new Int16Array(bytes(map.xy)), outcome = bytesOf(map.outcome);
    const size = map.spacing * 0.7;
    const square = new THREE.BoxGeometry(size, size, 0.004);
    const mesh = new THREE.InstancedMesh(square, new THREE.MeshBasicMaterial({ transparent: true, opacity: 0.75, depthWrite: false }), map.count);
    const matrix = new THREE.Matrix4(), colour = new THREE.Color();
    for (let i = 0; i < map.count; i++) {
      matrix.makeTranslation(xy[2 * i] / 1000, xy[2 * i + 1] / 1000, map.z + 0.004);
      mesh.setMatrixAt(i, matrix);
      mesh.setColorAt(i, colour.setHex(OUTCOME_COLOURS[map.outcomes[outcome[i]]] || 0x888888));
    }
    mesh.userData.map = map; mesh.userData.outcome = outcome; mesh.userData.xy = xy;
    mesh.renderOrder = 1;
    group.add(mesh);
    const marks = [];
    map.found.forEach(([x, y, yaw], i) => {  // the poses found: an arrow for the heading, the chosen one longest
      const z = map.z + 0.01, r = i === 0 ? 0.35 : 0.2, c = Math.cos(yaw), s = Math.sin(yaw);
      const tip = [x + c * r, y + s * r, z];
      marks.push([[x, y, z], tip], [tip, [tip[0] - c * 0.08 + s * 0.06, tip[1] - s * 0.08 - c * 0.06, z]],
        [tip, [tip[0] - c * 0.08 - s * 0.06, tip[1] - s * 0.08 + c * 0.06, z]]);
    });
    if (marks.length) group.add(lines(marks, 0x0b7285));
    const t = map.target;
    if (t) group.add(lines([[[t[0] - 0.06, t[1], t[2]], [t[0] + 0.06, t[1], t[2]]], [[t[0], t[1] - 0.06, t[2]], [t[0], t[1] + 0.06, t[2]]]], 0x000000));
    group.userData.squares = mesh;
    return group;
  }
  const drawnReasoning = new Map();  // step -> its Group (made when first shown)
  let reasoningStep = -1;
  function showReasoning(k) {
    if (k === reasoningStep) return;
    if (reasoningStep >= 0 && drawnReasoning.has(reasoningStep)) drawnReasoning.get(reasoningStep).visible = false;
    reasoningBodies = [];
    reasoningStep = k;
    const frame = frames[k] || {}, info = frame.reasoning, map = frame.candidates;
    const legend = $("reasonbox");
    legend.textContent = "";
    legend.hidden = true;
    document.body.dataset.reasoning = [info ? info.kind : "", map && map.count ? "candidates" : ""].filter(Boolean).join(",");
    if (!info && !(map && map.count)) { repaint(); return; }
    if (!drawnReasoning.has(k)) {
      const group = new THREE.Group();
      if (info && info.kind === "view") group.add(viewCone(info));
      if (info && info.kind === "reach" && info.target) {
        const t = info.target;
        group.add(lines([[[t[0] - 0.05, t[1], t[2]], [t[0] + 0.05, t[1], t[2]]], [[t[0], t[1] - 0.05, t[2]], [t[0], t[1] + 0.05, t[2]]],
          [[t[0], t[1], t[2] - 0.05], [t[0], t[1], t[2] + 0.05]]], info.reachable === false ? 0xe03131 : 0x2f9e44));
      }
      if (map && map.count) group.add(candidateMap(map));
      reasoning.add(group);
      drawnReasoning.set(k, group);
    }
    drawnReasoning.get(k).visible = true;
    const rows = [];
    if (info && info.kind === "view") {
      const seen = (info.seen || []).map((b) => bodies[b].name), hid = (info.occluders || []).map((b) => bodies[b].name);
      rows.push(el("div", {}, el("b", { text: "view cone" }), `${info.planned ? " the robot's camera will have from the pose chosen" : " of the robot's camera"}${seen.length ? ` on ${seen.join(", ")}` : ""}` +
        (info.fraction !== undefined ? `: ${(100 * info.fraction).toFixed(0)} % visible` : "") + (hid.length ? `, hidden by ${hid.join(", ")}` : "")));
      reasoningBodies = info.occluders || [];
    }
    if (info && info.kind === "reach") {
      const blockers = (info.blockers || []).map((b) => bodies[b].name);
      rows.push(el("div", {}, el("b", { text: "reach" }), info.reachable === null ? " target" : info.reachable ? ": reachable" : ": not reachable",
        blockers.length ? `; in the way: ${blockers.join(", ")}` : ""));
      reasoningBodies = info.blockers || [];
    }
    if (map && map.count) {
      const node = byPath.get(frame.path), location = node && node.data.location;
      const counts = location && location.ruled_out ? Object.entries(location.ruled_out).filter(([, n]) => n > 0) : [];
      const key = el("div", { class: "key" });
      for (const [name, n] of [["ok", (map.found || []).length], ...counts]) {
        const hex = (OUTCOME_COLOURS[name] || 0x888888).toString(16).padStart(6, "0");
        key.append(el("span", { class: "item" }, el("span", { class: "swatch", style: `background:#${hex}` }), ` ${name}${name === "ok" ? " (found)" : ` ${n}`}`));
      }
      rows.push(el("div", {}, el("b", { text: "candidates" }), ` ${location ? location.candidates : map.count} tried for ${map.kind === "base" ? "where to stand" : "a spot"}` +
        `, ${map.count} positions drawn (hover for why); arrow: the pose chosen`), key);
    }
    legend.append(...rows);
    legend.hidden = false;
    repaint();
  }
  const orange = new Map();
  function glowingOrange(material) { return tinted(orange, material, 0xf08c00, 0.6); }
  const tip = $("tooltip");
  view.addEventListener("pointermove", (event) => {  // hover over a candidate: its outcome and why
    const group = drawnReasoning.get(reasoningStep);
    const squares = group && group.visible && group.children.map((c) => c.userData.squares).find(Boolean);
    if (!squares || !renderer) { tip.hidden = true; return; }
    const rect = renderer.domElement.getBoundingClientRect();
    pointer.set(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(pointer, camera);
    const hit = raycaster.intersectObject(squares, false)[0];
    if (!hit) { tip.hidden = true; return; }
    const i = hit.instanceId, map = squares.userData.map;
    const why = map.why && map.why[String(i)];
    tip.textContent = `(${(squares.userData.xy[2 * i] / 1000).toFixed(2)}, ${(squares.userData.xy[2 * i + 1] / 1000).toFixed(2)}): ` +
      `${map.outcomes[squares.userData.outcome[i]]}${why ? ` (${why})` : ""}`;
    tip.style.left = `${event.clientX - rect.left + 12}px`;
    tip.style.top = `${event.clientY - rect.top + 12}px`;
    tip.hidden = false;
  });

  // ---------------------------------------------------------------- the camera stays above the floor; an image of the view
  if (controls) {
    controls.addEventListener("change", () => {
      if (camera.position.z < 0.05) { camera.position.z = 0.05; camera.lookAt(controls.target); }
      if (controls.target.z < 0) controls.target.z = 0;
    });
  }
  function exportPng(download) {
    if (!renderer) return;
    renderer.render(world, camera);
    const link = $("png-link");
    link.href = renderer.domElement.toDataURL("image/png");
    link.download = `${String(trace.plan || "plan").replace(/\.ya?ml$/, "")}-step-${shown}.png`;
    document.body.dataset.png = String(link.href.length);
    if (download) link.click();
  }
  $("png").addEventListener("click", () => exportPng(true));

  // ---------------------------------------------------------------- playing, seeking and what is shown
  let position = 0, playing = false, shown = -1, dirty = true, last = null;
  const scrub = $("scrub"), stepno = $("stepno"), playButton = $("play");
  scrub.max = String(STEPS);
  scrub.step = "any";
  stepno.max = String(STEPS);
  $("count").textContent = String(STEPS);

  function details(k) {
    const box = $("details");
    box.textContent = "";
    selection(box, k);
    if (k === 0) {
      box.prepend(el("h2", { text: "Before the first step" }),
        el("div", { text: `${STEPS} steps; press ▶ to play, or click a step in the tree or the timeline.` }));
      return;
    }
    const node = byPath.get(frames[k].path);
    if (!node) return;
    const head = box.firstChild;
    const data = node.data;
    box.insertBefore(el("h2", { text: `Step ${k} of ${STEPS}: ${label(data)}` }), head);
    const table = el("table");
    const add = (name, value) => { if (value !== undefined && value !== null && value !== "") table.append(el("tr", {}, el("td", { text: name }), el("td", {}, value))); };
    const pretty = (value) => {
      if (typeof value === "string") return value;
      const flat = JSON.stringify(value);
      if (flat === undefined || flat.length <= 90 || value === null || typeof value !== "object" || Array.isArray(value)) return flat;
      return Object.entries(value).map(([k, v]) => `${k}: ${JSON.stringify(v)}`).join("\n");
    };
    const code = (value) => el("code", { text: pretty(value) });
    add("path", code(data.path));
    add("status", el("span", { text: node.final }));
    add("took", seconds(data));
    const filled = (value) => value && typeof value === "object" && Object.keys(value).length > 0;
    if (data.designator) {
      if (filled(data.designator.slots)) add("slots", code(data.designator.slots));
      if (filled(data.designator.resolved)) add("resolved", code(data.designator.resolved));
    }
    const physics = frames[k].physics;
    if (physics && physics.length) add("physics", `${physics.length} frames over ${physics[physics.length - 1].t.toFixed(2)} s simulated (scrub through the step to see them)`);
    const whatif = frames[k].whatif;
    if (whatif && whatif.frames.length) add("simulated", `what the query tried out on a copy of the world: ${bodies[whatif.body].name} over ${whatif.frames[whatif.frames.length - 1].t.toFixed(2)} s (the amber ghost; the world itself did not move)`);
    if (data.query) { add("query", code(`${data.type}(${slots(data.query.args)})`)); add("answer", code(data.query.result)); add("details", code(data.query.details)); }
    if (data.condition) add("condition", code(condition(data.condition)));
    if (data.message !== undefined) add("message", code(data.message));
    if (data.bound) add("bound", code(data.bound));
    let action = node.parent;  // the action this step is part of: its expansion, this step marked
    while (action && action.data.type !== "action") action = action.parent;
    if (action) {
      const list = el("ol", { class: "expansion" });
      const walk = (n) => {
        for (const child of n.children) {
          const state = stateAt(child, k);
          list.append(el("li", { class: `st-${state}${child === node || (child.first <= k && k <= child.last && child.children.length) ? " here" : ""}` },
            `${ICON[state] || "?"} ${label(child.data)}`, child.children.length ? ` (${child.children.length} steps)` : ""));
        }
      };
      walk(action);
      add("expansion", el("span", {}, `${label(action.data)} → `, list));
    }
    let projecting = node.parent;  // a step the project step chose after projecting: its table
    while (projecting && !projecting.data.projection) projecting = projecting.parent;
    if (projecting && !kept) add("projected", projectionTable(projecting.data));
    const failure = data.failure;
    if (failure) {
      const fatal = node.final !== "recovered";
      add("failure", el("span", {}, el("span", { class: `tag ${fatal ? "fatal" : "recovered"}`, text: fatal ? "fatal" : "recovered" }), " ",
        code(`${failure.type}: ${failure.message}`)));
    }
    box.insertBefore(table, head);
  }

  function selection(box, k) {  // the selected body at step k: its pose and what the step did to it
    if (selected < 0) return;
    const b = selected, body = bodies[b], at = bodyPose(b);
    const moved = k > 0 && [frames[k].poses || [], ...(frames[k].physics || []).map((f) => f.poses || [])]
      .some((flat) => { for (let i = 0; i < flat.length; i += 9) if (flat[i] === b) return true; return false; });
    const roles = [];
    if (activeFailure && activeFailure.objects.includes(b)) roles.push("the failed step's object");
    if (activeFailure && activeFailure.ghost && activeFailure.ghost.body === b) roles.push("its meant pose: the green ghost");
    const table = el("table", { class: "selection" });
    const row = (name, value) => table.append(el("tr", {}, el("td", { text: name }), el("td", { text: value })));
    row("position", `[${at.position.map((v) => v.toFixed(3)).join(", ")}] m`);
    row("tilt", `${at.tilt.toFixed(1)}° from upright, heading ${at.yaw.toFixed(1)}°`);
    row("this step", moved ? "moved it" : "did not move it");
    if (roles.length) row("in the failure", roles.join("; "));
    box.append(el("h2", {}, `Selected: ${body.name} `, el("span", { class: "hint", text: body.type })), table);
    document.body.dataset.selectedPose = [...at.position.map((v) => v.toFixed(4)), at.tilt.toFixed(2)].join(",");
  }

  function shortPath(path) {  // the last parts of a long path
    const parts = String(path || "").split("/");
    return parts.length > 4 ? "…/" + parts.slice(-4).join("/") : String(path || "");
  }
  const stepAt = (t) => Math.max(0, Math.min(STEPS, Math.ceil(t - 1e-6)));  // between two frames: the step going on

  function showStep(k, force) {
    if (k === shown && !force) return;
    shown = k;
    if (Math.abs(Number(scrub.value) - position) > 1e-6) scrub.value = String(position);
    stepno.value = String(k);
    document.body.dataset.step = String(k);
    const current = k > 0 ? byPath.get(frames[k].path) : null;
    const above = new Set();
    for (let up = current && current.parent; up; up = up.parent) above.add(up);
    for (const node of nodes) {
      const state = stateAt(node, k);
      node.li.className = `st-${state}` + (node === current ? " current" : "") + (above.has(node) ? " ancestor" : "") +
        (node.li.classList.contains("folded") ? " folded" : "");
      node.li.firstChild.children[1].textContent = ICON[state] || "?";
    }
    if (current) {
      const row = current.li.firstChild, box = $("tree");
      const top = row.offsetTop - box.offsetTop;
      if (top < box.scrollTop || top > box.scrollTop + box.clientHeight - 24) box.scrollTop = top - box.clientHeight / 3;
    }
    const x = xOf(frameTime[k]);
    cursor.setAttribute("x1", x); cursor.setAttribute("x2", x);
    if (current && current.row >= 0) {
      currentRow.setAttribute("y", current.row * ROW);
      currentRow.setAttribute("visibility", "visible");
      const box = $("timeline"), y = current.row * ROW;
      if (y < box.scrollTop || y > box.scrollTop + box.clientHeight - 40) box.scrollTop = y - box.clientHeight / 3;
    } else {
      currentRow.setAttribute("visibility", "hidden");
    }
    $("caption").innerHTML = "";
    $("caption").append(k === 0 ? el("span", { text: "before the first step" }) :
      el("span", {}, el("b", { text: `step ${k}/${STEPS} ${current ? label(current.data) : ""} ` }),
        `${current ? describe(current.data) : ""}`, el("span", { class: "path", text: `  ${shortPath(frames[k].path)}` })));
    showFailure(k);
    showReasoning(k);
    details(k);
  }

  function seek(k) {
    playing = false;
    playButton.textContent = "▶";
    position = Math.max(0, Math.min(STEPS, Number(k) || 0));
    pose(position);
    showStep(stepAt(position));
    dirty = true;
  }
  function stepSeconds(k) {  // a step that moved nothing passes quickly; physics plays about as fast as it ran
    const next = frames[Math.min(STEPS, k + 1)];
    const physics = next && next.physics && next.physics.length ? next.physics[next.physics.length - 1].t : 0;
    return (physics ? 0.5 + physics : next && next.poses && next.poses.length ? 0.9 : 0.3) / Number($("speed").value);
  }
  function tick() {  // playing runs on a timer: it goes on where no frames are drawn (a hidden tab, a headless browser)
    const now = performance.now();
    if (playing && last !== null) {
      position += (now - last) / 1000 / stepSeconds(Math.floor(position));
      if (position >= STEPS) { position = STEPS; playing = false; playButton.textContent = "▶"; }
      pose(position);
      showStep(stepAt(position));
      dirty = true;
    }
    last = now;
  }
  function draw() {  // drawing follows the browser's frames
    if (dirty && renderer) { renderer.render(world, camera); placeLabels(); dirty = false; }
    requestAnimationFrame(draw);
  }

  playButton.addEventListener("click", () => {
    if (!playing && position >= STEPS) position = 0;
    playing = !playing;
    playButton.textContent = playing ? "❚❚" : "▶";
  });
  $("first").addEventListener("click", () => seek(0));
  $("last").addEventListener("click", () => seek(STEPS));
  $("prev").addEventListener("click", () => seek(Math.ceil(position) - 1));
  $("next").addEventListener("click", () => seek(Math.floor(position) + 1));
  scrub.addEventListener("input", () => seek(Number(scrub.value)));
  stepno.addEventListener("change", () => seek(Number(stepno.value) || 0));
  document.addEventListener("keydown", (event) => {
    if (event.target.tagName === "INPUT" || event.target.tagName === "SELECT") return;
    if (event.key === " ") { playButton.click(); event.preventDefault(); }
    else if (event.key === "ArrowRight") seek(Math.floor(position) + 1);
    else if (event.key === "ArrowLeft") seek(Math.ceil(position) - 1);
    else if (event.key === "Home") seek(0);
    else if (event.key === "End") seek(STEPS);
    else if (event.key === "f") goToNextFailure();
  });
  function fromHash(opening) {
    const hash = decodeURIComponent(location.hash);
    const match = /step=(\d+(?:\.\d+)?|last)/.exec(hash);
    const nth = /failure=(\d+)/.exec(hash);  // the N-th failed step (1: the first), recovered ones too
    const path = /node=([^&]*)/.exec(hash);  // a node by its path: a step's frame, a composite's first step
    if (match) seek(match[1] === "last" ? STEPS : Number(match[1]));
    else if (path && byPath.has(path[1])) seek(stepOf(byPath.get(path[1])));
    else if (nth && failures[Number(nth[1]) - 1]) seek(failures[Number(nth[1]) - 1].step);
    else if (opening) {  // a failed run opens at its failure
      const fatal = failures.filter((f) => f.fatal).pop();
      if (fatal) seek(fatal.step);
    }
    const hide = /hide=([^&]*)/.exec(hash);
    if (hide) for (const name of hide[1].split(",")) if (bodyIndex.has(name)) setHidden(bodyIndex.get(name), true);
    const chosen = /select=([^&]*)/.exec(hash);
    if (chosen && bodyIndex.has(chosen[1])) select(bodyIndex.get(chosen[1]));
    if (/\bplay\b/.test(hash) && !playing) playButton.click();
    if (/\bpng\b/.test(hash)) exportPng(false);
  }
  window.addEventListener("hashchange", () => fromHash(false));

  resize();
  pose(0);
  showStep(0, true);
  fromHash(true);
  if (renderer) { renderer.render(world, camera); placeLabels(); }
  dirty = false;
  // for a page that embeds this one (or a test): go to a step, tell the step, select a body
  window.pycramReport = { seek, step: () => shown, position: () => position, select: (name) => select(bodyIndex.has(name) ? bodyIndex.get(name) : -1),
    stepOf: (path) => (byPath.has(path) ? stepOf(byPath.get(path)) : null) };
  document.body.dataset.steps = String(STEPS);
  document.body.dataset.projected = kept ? opened.join("|") : "";
  document.body.dataset.ready = "1";
  setInterval(tick, 30);
  requestAnimationFrame(draw);
})();
// Held in another page (`trace diff --report`): it moves this report with {pycram: "goto", step} and is told the step shown.
(function () {
  if (window.parent === window) return;
  const tell = () => window.parent.postMessage({ pycram: "step", step: Number(document.body.dataset.step) }, "*");
  window.addEventListener("message", (event) => {
    if (event.source !== window.parent || !event.data || event.data.pycram !== "goto") return;
    const box = document.getElementById("stepno");
    box.value = String(event.data.step);
    box.dispatchEvent(new Event("change"));
  });
  new MutationObserver(tell).observe(document.body, { attributes: true, attributeFilter: ["data-step"] });
  tell();
})();
