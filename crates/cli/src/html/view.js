// The 3D view of `hdot simulate --html`: draws the scene's bodies on a
// <canvas> at each frame of the run, each turned and placed where it is,
// with a small perspective projection (no library), the space axes,
// gravity, a top's axis trace or a free body's angular momentum, the paths
// of bodies the view follows, and runs play/pause, speed and the time
// scrubber. The view is turned so that up (against gravity) is up.
// Data: the JSON in <script id="motion"> (see crates/cli/src/html/simulation.rs).
"use strict";
(function () {
  const D = JSON.parse(document.getElementById("motion").textContent);
  const canvas = document.getElementById("view");
  const ctx = canvas.getContext("2d");
  const play = document.getElementById("play");
  const speed = document.getElementById("speed");
  const scrub = document.getElementById("scrub");
  const timeOut = document.getElementById("time");
  const n = D.t.length;
  const T = D.t[n - 1] - D.t[0];
  const S = D.scale;
  // The whole run plays in `span` seconds at ×1: its own duration, kept
  // between 6 s and 30 s so that a fast or long run can still be watched.
  const span = Math.min(Math.max(T, 6), 30);
  const COLOURS = [[70, 120, 190], [200, 110, 60], [70, 160, 100], [150, 90, 190]];
  let az = -0.6, el = 0.35, frame = 0, playing = true, last = null;

  // -- meshes: each part a list of faces (arrays of local points) --
  function ring(r, z, k) {
    const p = [];
    for (let i = 0; i < k; i++) {
      const a = (2 * Math.PI * i) / k;
      p.push([r * Math.cos(a), r * Math.sin(a), z]);
    }
    return p;
  }
  function prism(bottom, top) {
    const f = [];
    const k = bottom.length;
    for (let i = 0; i < k; i++) {
      const j = (i + 1) % k;
      f.push({ pts: [bottom[i], bottom[j], top[j], top[i]], dark: i < k / 4 });
    }
    f.push({ pts: bottom.slice().reverse() }, { pts: top });
    return f;
  }
  function mesh(part) {
    const d = part.d;
    switch (part.k) {
      case "box": {
        const [a, b, c] = d.map((v) => v / 2);
        const bottom = [[-a, -b, -c], [a, -b, -c], [a, b, -c], [-a, b, -c]];
        const top = bottom.map((p) => [p[0], p[1], c]);
        const f = prism(bottom, top);
        f[0].dark = true;
        return { faces: f };
      }
      case "cylinder":
        return { faces: prism(ring(d[0], -d[1] / 2, 28), ring(d[0], d[1] / 2, 28)) };
      case "disk":
        return { faces: prism(ring(d[0], -0.02 * d[0], 32), ring(d[0], 0.02 * d[0], 32)) };
      case "cone": {
        const base = ring(d[0], -d[1] / 4, 28);
        const apex = [0, 0, (3 * d[1]) / 4];
        const f = base.map((p, i) => ({ pts: [p, base[(i + 1) % 28], apex], dark: i < 7 }));
        f.push({ pts: base.slice().reverse() });
        return { faces: f };
      }
      case "sphere": {
        const f = [];
        const r = d[0], la = 10, lo = 18;
        const at = (i, j) => {
          const th = (Math.PI * i) / la, ph = (2 * Math.PI * j) / lo;
          return [r * Math.sin(th) * Math.cos(ph), r * Math.sin(th) * Math.sin(ph), r * Math.cos(th)];
        };
        for (let i = 0; i < la; i++)
          for (let j = 0; j < lo; j++)
            f.push({ pts: [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)], dark: j < lo / 4 });
        return { faces: f };
      }
      case "ring":
        return { line: ring(d[0], 0, 48).concat([[d[0], 0, 0]]) };
      case "rod":
        return { line: [[-d[0] / 2, 0, 0], [d[0] / 2, 0, 0]] };
      default:
        return { dot: true };
    }
  }
  const groups = D.groups.map((g, gi) => ({
    rot: g.rot,
    pos: g.pos,
    colour: COLOURS[gi % COLOURS.length],
    parts: g.parts.map((p) => ({ p: p.p, r: p.r, m: mesh(p) })),
  }));

  // -- linear algebra on 3-vectors and row-major 3×3 matrices --
  const mul = (m, o, v) => [
    m[o] * v[0] + m[o + 1] * v[1] + m[o + 2] * v[2],
    m[o + 3] * v[0] + m[o + 4] * v[1] + m[o + 5] * v[2],
    m[o + 6] * v[0] + m[o + 7] * v[1] + m[o + 8] * v[2],
  ];
  const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const at3 = (a, i) => (a ? [a[3 * i], a[3 * i + 1], a[3 * i + 2]] : [0, 0, 0]);

  // -- space → view: about the view's centre at frame i (the origin, or
  // the bodies it follows), turned by D.view so that up is +Z --
  const V = D.view || [1, 0, 0, 0, 1, 0, 0, 0, 1];
  const dir = (v) => mul(V, 0, v);
  const toView = (p, i) => mul(V, 0, sub(p, at3(D.centre, i)));
  // The paths the view draws when it follows the bodies: one per place.
  const paths = [];
  if (D.centre)
    for (const g of groups)
      if (g.pos && !paths.some((p) => p.pos.every((v, k) => v === g.pos[k])))
        paths.push({ pos: g.pos, colour: g.colour });

  // -- the camera: turned by az about Z and tipped by el, perspective --
  let W = 0, H = 0, dpr = 1;
  function camera(p) {
    const ca = Math.cos(az), sa = Math.sin(az), ce = Math.cos(el), se = Math.sin(el);
    const x = ca * p[0] - sa * p[1];
    const y = sa * p[0] + ca * p[1];
    // screen right = x, screen up = z tipped towards the viewer, depth = y.
    const up = ce * p[2] - se * y;
    const depth = se * p[2] + ce * y;
    const f = 1 / (1 + (0.25 * depth) / S);
    const k = (0.32 * Math.min(W, H)) / S;
    return [W / 2 + k * f * x, H / 2 - k * f * up, depth];
  }
  function arrow(from, to, colour, label) {
    const a = camera(from), b = camera(to);
    ctx.strokeStyle = ctx.fillStyle = colour;
    ctx.lineWidth = 2 * dpr;
    ctx.beginPath();
    ctx.moveTo(a[0], a[1]);
    ctx.lineTo(b[0], b[1]);
    ctx.stroke();
    const ang = Math.atan2(b[1] - a[1], b[0] - a[0]), h = 9 * dpr;
    ctx.beginPath();
    ctx.moveTo(b[0], b[1]);
    ctx.lineTo(b[0] - h * Math.cos(ang - 0.4), b[1] - h * Math.sin(ang - 0.4));
    ctx.lineTo(b[0] - h * Math.cos(ang + 0.4), b[1] - h * Math.sin(ang + 0.4));
    ctx.fill();
    // The label on a halo of the background, legible over a body.
    ctx.font = 13 * dpr + "px sans-serif";
    ctx.lineWidth = 3 * dpr;
    ctx.strokeStyle = "rgba(251, 251, 248, 0.85)";
    ctx.strokeText(label, b[0] + 4 * dpr, b[1] - 4 * dpr);
    ctx.fillText(label, b[0] + 4 * dpr, b[1] - 4 * dpr);
  }
  const light = [0.4, -0.5, 0.77];

  function draw() {
    ctx.fillStyle = "#fbfbf8";
    ctx.fillRect(0, 0, W, H);
    const o = [0, 0, 0];
    // The space axes from the origin, or, when the view follows the
    // bodies, small in a corner (their directions only).
    const axes = D.centre ? [[1.1 * S, 1.1 * S, -0.9 * S], 0.35 * S] : [o, 1.25 * S];
    for (const [v, name] of [[[1, 0, 0], "X"], [[0, 1, 0], "Y"], [[0, 0, 1], "Z"]])
      arrow(axes[0], add(axes[0], dir(v).map((c) => axes[1] * c)), "#888", name);
    if (D.g) {
      const base = [-1.1 * S, -1.1 * S, 0.9 * S];
      arrow(base, add(base, dir(D.g).map((c) => 0.5 * S * c)), "#b45309", "g");
    }
    for (const p of paths) {
      ctx.strokeStyle = "rgba(" + p.colour.join(",") + ", 0.6)";
      ctx.lineWidth = 1.5 * dpr;
      ctx.beginPath();
      for (let i = 0; i <= frame; i++) {
        const c = camera(toView(at3(p.pos, i), frame));
        i ? ctx.lineTo(c[0], c[1]) : ctx.moveTo(c[0], c[1]);
      }
      ctx.stroke();
    }
    if (D.bearings) {
      const [a, b] = D.bearings.map((z) => camera(toView([0, 0, z], frame)));
      ctx.strokeStyle = "#555";
      ctx.lineWidth = 3 * dpr;
      ctx.beginPath();
      ctx.moveTo(a[0], a[1]);
      ctx.lineTo(b[0], b[1]);
      ctx.stroke();
      ctx.fillStyle = "#555";
      for (const [p, name] of [[a, "A"], [b, "B"]]) {
        ctx.fillRect(p[0] - 5 * dpr, p[1] - 5 * dpr, 10 * dpr, 10 * dpr);
        ctx.fillText(name, p[0] + 8 * dpr, p[1]);
      }
    }
    const faces = [], lines = [];
    for (const g of groups) {
      const o9 = 9 * frame;
      const here = at3(g.pos, frame);
      const world = (part, q) => toView(add(here, mul(g.rot, o9, add(part.p, mul(part.r, 0, q)))), frame);
      for (const part of g.parts) {
        const m = part.m;
        if (m.faces)
          for (const f of m.faces) {
            const w = f.pts.map((q) => world(part, q));
            const nrm = cross(sub(w[1], w[0]), sub(w[2], w[0]));
            const len = Math.hypot(nrm[0], nrm[1], nrm[2]) || 1;
            const lit = Math.abs((nrm[0] * light[0] + nrm[1] * light[1] + nrm[2] * light[2]) / len);
            const s = (0.45 + 0.55 * lit) * (f.dark ? 0.6 : 1);
            const c = w.map(camera);
            const depth = c.reduce((acc, p) => acc + p[2], 0) / c.length;
            faces.push({ c, depth, fill: "rgb(" + g.colour.map((v) => Math.round(v * s + 40 * (1 - s))).join(",") + ")" });
          }
        else if (m.line) lines.push({ c: m.line.map((q) => camera(world(part, q))), colour: g.colour });
        else lines.push({ c: [camera(world(part, [0, 0, 0]))], colour: g.colour, dot: true });
      }
    }
    faces.sort((a, b) => b.depth - a.depth);
    ctx.lineJoin = "round";
    for (const f of faces) {
      ctx.fillStyle = ctx.strokeStyle = f.fill;
      ctx.lineWidth = 0.5 * dpr;
      ctx.beginPath();
      f.c.forEach((p, i) => (i ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1])));
      ctx.closePath();
      ctx.fill();
      ctx.stroke();
    }
    for (const l of lines) {
      ctx.strokeStyle = ctx.fillStyle = "rgb(" + l.colour.join(",") + ")";
      if (l.dot) {
        ctx.beginPath();
        ctx.arc(l.c[0][0], l.c[0][1], 4 * dpr, 0, 2 * Math.PI);
        ctx.fill();
        continue;
      }
      ctx.lineWidth = 4 * dpr;
      ctx.beginPath();
      l.c.forEach((p, i) => (i ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1])));
      ctx.stroke();
    }
    if (D.axis && groups.length) {
      // The trace of the top's axis tip up to now: the nutation curve.
      const rot = groups[0].rot;
      ctx.strokeStyle = "#be123c";
      ctx.lineWidth = 1.5 * dpr;
      ctx.beginPath();
      for (let i = 0; i <= frame; i++) {
        const p = camera(toView(mul(rot, 9 * i, D.axis), frame));
        i ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1]);
      }
      ctx.stroke();
      arrow(o, toView(mul(rot, 9 * frame, D.axis), frame), "#be123c", "axis");
    }
    // H reaches past the body (S is the body's reach), within the view.
    if (D.momentum) arrow(o, dir(D.momentum).map((c) => 1.45 * S * c), "#15803d", "H");
    timeOut.textContent = "t = " + D.t[frame].toFixed(3) + " s";
    scrub.value = frame;
  }

  function resize() {
    dpr = window.devicePixelRatio || 1;
    const w = canvas.clientWidth;
    canvas.style.height = Math.round(Math.min(0.66 * w, 520)) + "px";
    W = canvas.width = Math.round(w * dpr);
    H = canvas.height = Math.round(canvas.clientHeight * dpr);
    draw();
  }
  function tick(now) {
    if (playing && last !== null) {
      const step = ((now - last) / 1000) * (n - 1) / span * Number(speed.value);
      frame = Math.floor(frame + step) % n;
      if (step < 1) { requestAnimationFrame(tick); return; }
    }
    last = now;
    if (playing) draw();
    requestAnimationFrame(tick);
  }
  play.addEventListener("click", () => {
    playing = !playing;
    play.textContent = playing ? "Pause" : "Play";
    last = null;
  });
  scrub.addEventListener("input", () => {
    frame = Number(scrub.value);
    draw();
  });
  let drag = null;
  canvas.addEventListener("pointerdown", (e) => (drag = [e.clientX, e.clientY, az, el]));
  window.addEventListener("pointerup", () => (drag = null));
  canvas.addEventListener("pointermove", (e) => {
    if (!drag) return;
    az = drag[2] - (e.clientX - drag[0]) / 150;
    el = Math.max(-1.5, Math.min(1.5, drag[3] + (e.clientY - drag[1]) / 150));
    draw();
  });
  const legend = ["Drag the view to turn it. The whole run plays in " + span.toFixed(0) + " s at ×1."];
  if (D.axis) legend.push("Red: the axis of the top and the trace of its tip.");
  if (D.momentum) legend.push("Green: the angular momentum H, fixed in space.");
  if (D.g) legend.push("Brown: gravity.");
  if (D.centre) legend.push("The view follows the bodies; thin lines: the paths of their reference points.");
  document.getElementById("legend").textContent = legend.concat(D.notes).join(" ");
  window.addEventListener("resize", resize);
  resize();
  requestAnimationFrame(tick);
})();
