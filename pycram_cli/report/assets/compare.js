// Two replay reports side by side (see pycram_cli/report/compare.py): one set of controls moves both to the same
// step; stepping or playing in either report moves the other; the first divergence is marked and shown first.
(function () {
  "use strict";
  const $ = (id) => document.getElementById(id);
  const data = JSON.parse($("diff-data").textContent);
  const frames = { a: $("frame-a"), b: $("frame-b") };
  const STEPS = Math.max(data.a.steps, data.b.steps);
  const byStep = new Map(data.differences.map((d) => [d.step, d.notes]));
  const shown = { a: null, b: null };
  const asked = /step=(\d+)/.exec(location.hash);  // `diff.html#step=N` opens at step N
  let current = asked ? Math.min(STEPS, Number(asked[1])) : data.divergence === null ? 0 : data.divergence;

  function el(tag, attrs, ...children) {
    const node = document.createElement(tag);
    for (const [key, value] of Object.entries(attrs || {})) {
      if (key === "text") node.textContent = value; else node.setAttribute(key, value);
    }
    node.append(...children);
    return node;
  }
  function run(side) {
    const r = data[side];
    const params = Object.keys(r.params).length ? " " + JSON.stringify(r.params) : "";
    const box = $(`run-${side}`);
    box.append(el("b", { text: `${side.toUpperCase()}: ${r.name} ` }), el("span", { class: `badge ${r.status}`, text: r.status }),
      ` ${r.plan} on ${r.world}, ${r.steps} steps${params}`);
    if (r.failure) box.append(el("div", { class: "failure", text: r.failure }));
    box.title = box.textContent;
  }
  $("title").textContent = data.divergence === null ? "The two runs did the same at every step" :
    `The runs differ first at step ${data.divergence}` + (data.divergence === 0 ? " (before the first step)" : "");
  run("a"); run("b");
  document.body.dataset.divergence = data.divergence === null ? "none" : String(data.divergence);

  const cells = [];
  for (let k = 0; k <= STEPS; k++) {
    const cell = el("span", { title: byStep.has(k) ? `step ${k}: ${byStep.get(k).join("; ")}` : `step ${k}: the same` });
    if (byStep.has(k)) cell.classList.add(k === data.divergence ? "divergence" : "differ");
    cell.addEventListener("click", () => go(k));
    cells.push(cell);
    $("steps").append(cell);
  }
  $("scrub").max = String(STEPS);
  $("stepno").max = String(STEPS);
  $("count").textContent = String(STEPS);
  $("divergence-button").disabled = data.divergence === null;

  function show(k) {
    $("scrub").value = String(k);
    $("stepno").value = String(k);
    document.body.dataset.step = String(k);
    cells.forEach((cell, i) => cell.classList.toggle("current", i === k));
    const notes = $("notes");
    notes.innerHTML = "";
    if (byStep.has(k)) {
      notes.append(el("span", { class: "differ", text: k === data.divergence ? `step ${k}: the first divergence` : `step ${k}: the runs differ` }),
        el("ul", {}, ...byStep.get(k).map((note) => el("li", { text: note }))));
    } else {
      notes.append(el("span", { class: "same", text: `step ${k}: both runs did the same` }));
    }
  }
  function tell(side) {
    if (shown[side] === null) return;  // not loaded yet: told once it is
    frames[side].contentWindow.postMessage({ pycram: "goto", step: Math.min(current, data[side].steps) }, "*");
  }
  function go(k, from) {  // `from`: the report that moved there itself, which is not told again
    current = Math.max(0, Math.min(STEPS, Math.round(k)));
    show(current);
    for (const side of ["a", "b"]) if (side !== from) tell(side);
  }
  window.addEventListener("message", (event) => {
    const side = event.source === frames.a.contentWindow ? "a" : event.source === frames.b.contentWindow ? "b" : null;
    if (!side || !event.data || event.data.pycram !== "step") return;
    const first = shown[side] === null;
    shown[side] = Number(event.data.step);
    document.body.dataset[`${side}Step`] = String(shown[side]);
    if (first) {
      tell(side);
      if (shown.a !== null && shown.b !== null) document.body.dataset.ready = "1";
    } else if (shown[side] !== Math.min(current, data[side].steps)) {
      go(shown[side], side);
    }
  });
  $("first").addEventListener("click", () => go(0));
  $("last").addEventListener("click", () => go(STEPS));
  $("prev").addEventListener("click", () => go(current - 1));
  $("next").addEventListener("click", () => go(current + 1));
  $("scrub").addEventListener("input", () => go(Number($("scrub").value)));
  $("stepno").addEventListener("change", () => go(Number($("stepno").value) || 0));
  $("divergence-button").addEventListener("click", () => go(data.divergence || 0));
  document.addEventListener("keydown", (event) => {
    if (event.target.tagName === "INPUT") return;
    if (event.key === "ArrowRight") go(current + 1);
    else if (event.key === "ArrowLeft") go(current - 1);
  });
  show(current);
  frames.a.srcdoc = JSON.parse($("page-a").textContent);
  frames.b.srcdoc = JSON.parse($("page-b").textContent);
})();
