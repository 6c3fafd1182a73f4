// Lucent browser client: the presenter's pointer (a laser dot) and marks
// (arrow, circle, freehand, text) drawn over the frame. Marks come anchored in
// the patient (LPS mm) and are projected onto every frame with the frame's own
// `projection` (docs/protocol.md, "Pointer and marks"), so they stay on the
// anatomy when the presenter turns the view; the pointer is in screen space.
// The presenter's toolbar picks a tool whose gestures send pointer and mark
// messages instead of turning the view.
"use strict";

window.createLucentMarks = (canvas, canvasView, options) => {
  const kMarkColour = "#ff2bd6";
  const kPointerColour = "#ff3b30";
  const kPointerIntervalMs = 33; // ~30 pointer updates a second (the server allows 60)
  const kMaxFreehandPoints = 512;
  const toolbar = options.toolbar;
  const textInput = options.textInput;

  const marks = new Map(); // id -> {id, kind, anchors, text}
  let pointer = null;      // {x, y}: fractions of the presenter's view
  let rect = null;         // where the last frame lies on the canvas (canvas pixels)
  let projection = null;   // the last frame's 3 x 4 matrix
  let enabled = false;     // this page presents (and its connection speaks version 4)
  let tool = "";           // "" (turn the view), pointer, arrow, circle, freehand, text
  let gesture = null;      // {kind, points} while a mark is being drawn
  let lastPointerSent = 0;

  // --- drawing ---------------------------------------------------------------

  // LPS mm to image fractions through the frame's projection; null behind the eye.
  function project(p) {
    const m = projection;
    const w = m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11];
    if (!(w > 1e-9)) {
      return null;
    }
    return [(m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3]) / w,
            (m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7]) / w];
  }
  function toCanvas(f) {
    return [rect.x + f[0] * rect.w, rect.y + f[1] * rect.h];
  }
  function fractionsOf(mark) {
    if (!projection) {
      return null;
    }
    const fractions = mark.anchors.map(project);
    return fractions.every((f) => f !== null) ? fractions : null;
  }

  function drawShape(context, kind, points, text) {
    const [a, b] = points;
    context.beginPath();
    if (kind === "arrow") { // tip, tail
      context.moveTo(b[0], b[1]);
      context.lineTo(a[0], a[1]);
      const angle = Math.atan2(a[1] - b[1], a[0] - b[0]);
      const head = Math.max(8, rect.h / 30);
      for (const side of [-0.45, 0.45]) {
        context.moveTo(a[0], a[1]);
        context.lineTo(a[0] - head * Math.cos(angle + side), a[1] - head * Math.sin(angle + side));
      }
    } else if (kind === "circle") { // centre, a point of the rim
      context.arc(a[0], a[1], Math.hypot(b[0] - a[0], b[1] - a[1]), 0, 2 * Math.PI);
    } else if (kind === "freehand") {
      points.forEach((p, n) => (n === 0 ? context.moveTo(p[0], p[1]) : context.lineTo(p[0], p[1])));
    }
    context.stroke();
    // The anchor of the mark (an arrow's tip, a circle's centre, where text stands).
    context.beginPath();
    context.arc(a[0], a[1], Math.max(3, rect.h / 120), 0, 2 * Math.PI);
    context.fill();
    if (kind === "text") {
      context.strokeText(text, a[0] + 8, a[1] - 8);
      context.fillText(text, a[0] + 8, a[1] - 8);
    }
  }

  // Called by the view after it has drawn a frame at `frameRect`.
  function draw(context, frameRect, header) {
    rect = frameRect;
    projection = header && Array.isArray(header.projection) ? header.projection : null;
    context.save();
    context.lineWidth = Math.max(2, rect.h / 250);
    context.lineJoin = context.lineCap = "round";
    context.strokeStyle = context.fillStyle = kMarkColour;
    context.font = Math.round(Math.max(12, rect.h / 28)) + "px sans-serif";
    for (const mark of marks.values()) {
      const fractions = fractionsOf(mark);
      if (fractions) {
        drawShape(context, mark.kind, fractions.map(toCanvas), mark.text);
      }
    }
    if (gesture && gesture.points.length > 1) {
      drawShape(context, gesture.kind, gesture.points.map(toCanvas), "");
    }
    if (pointer) {
      const [x, y] = toCanvas([pointer.x, pointer.y]);
      const r = Math.max(5, rect.h / 80);
      context.shadowColor = kPointerColour;
      context.shadowBlur = 3 * r;
      context.fillStyle = kPointerColour;
      context.beginPath();
      context.arc(x, y, r, 0, 2 * Math.PI);
      context.fill();
    }
    context.restore();
  }

  // --- messages ----------------------------------------------------------------

  // pointer, mark, marks-cleared: true when it was one of them.
  function handle(message) {
    if (message.type === "pointer") {
      pointer = typeof message.x === "number" ? { x: message.x, y: message.y } : null;
    } else if (message.type === "mark") {
      marks.set(message.id, { id: message.id, kind: message.kind, anchors: message.anchors,
                              text: message.text || "" });
    } else if (message.type === "marks-cleared") {
      marks.clear();
    } else {
      return false;
    }
    canvasView.redraw();
    return true;
  }

  // Another series, another session: its marks are not ours.
  function reset() {
    marks.clear();
    pointer = null;
    gesture = null;
    canvasView.redraw();
  }

  // --- the presenter's gestures ---------------------------------------------

  function fractionAt(event) {
    const box = canvas.getBoundingClientRect();
    const x = (event.clientX - box.left) * canvas.width / Math.max(1, box.width);
    const y = (event.clientY - box.top) * canvas.height / Math.max(1, box.height);
    const r = rect || { x: 0, y: 0, w: canvas.width, h: canvas.height };
    const clamp = (v) => Math.min(1, Math.max(0, v));
    return [clamp((x - r.x) / r.w), clamp((y - r.y) / r.h)];
  }
  function sendPointer(f, now) {
    if (now - lastPointerSent >= kPointerIntervalMs) {
      lastPointerSent = now;
      options.send({ type: "pointer", x: f[0], y: f[1] });
    }
  }
  function active() {
    return enabled && tool !== "";
  }

  // Capture phase: a tool's gesture never reaches the view's rotate and pan.
  canvas.addEventListener("pointerdown", (event) => {
    if (!active()) {
      return;
    }
    event.stopImmediatePropagation();
    event.preventDefault();
    const f = fractionAt(event);
    if (tool === "pointer") {
      sendPointer(f, Infinity);
    } else if (tool === "text") {
      const text = textInput.value.trim();
      if (text) {
        options.send({ type: "mark", kind: "text", points: [f], text: text.slice(0, 200) });
      }
    } else {
      canvas.setPointerCapture(event.pointerId);
      gesture = { kind: tool, points: tool === "freehand" ? [f] : [f, f] };
    }
  }, { capture: true });

  canvas.addEventListener("pointermove", (event) => {
    if (!active()) {
      return;
    }
    event.stopImmediatePropagation();
    const f = fractionAt(event);
    if (tool === "pointer") {
      sendPointer(f, performance.now());
    } else if (gesture && gesture.kind === "freehand") {
      const last = gesture.points[gesture.points.length - 1];
      if (gesture.points.length < kMaxFreehandPoints &&
          Math.hypot(f[0] - last[0], f[1] - last[1]) > 0.004) {
        gesture.points.push(f);
        canvasView.redraw();
      }
    } else if (gesture) {
      // An arrow points where the drag ends: tip first, then the tail where it began.
      gesture.points[gesture.kind === "arrow" ? 0 : 1] = f;
      canvasView.redraw();
    }
  }, { capture: true });

  function finish(event) {
    if (!active()) {
      return;
    }
    event.stopImmediatePropagation();
    if (gesture && gesture.kind !== "freehand" && event.type === "pointerup") {
      gesture.points[gesture.kind === "arrow" ? 0 : 1] = fractionAt(event); // where it ended
    }
    if (gesture && gesture.points.length >= 2) {
      options.send({ type: "mark", kind: gesture.kind, points: gesture.points });
    }
    gesture = null;
    canvasView.redraw();
  }
  canvas.addEventListener("pointerup", finish, { capture: true });
  canvas.addEventListener("pointercancel", finish, { capture: true });
  canvas.addEventListener("pointerleave", () => {
    if (active() && tool === "pointer") {
      options.send({ type: "pointer" }); // the dot goes when the cursor leaves the view
    }
  });

  function selectTool(name) {
    if (tool === "pointer" && name !== "pointer") {
      options.send({ type: "pointer" });
    }
    tool = name;
    for (const button of toolbar.querySelectorAll("button[data-tool]")) {
      button.setAttribute("aria-pressed", String(button.dataset.tool === tool));
    }
    textInput.hidden = tool !== "text";
    canvas.classList.toggle("marking", tool !== "");
  }
  for (const button of toolbar.querySelectorAll("button[data-tool]")) {
    button.addEventListener("click", () => selectTool(button.dataset.tool));
  }
  toolbar.querySelector("[data-action=clear]").addEventListener("click", () => {
    options.send({ type: "marks-clear" });
  });

  return {
    draw,
    handle,
    reset,
    // The toolbar is the presenter's (on a version 4 connection).
    setEnabled(on) {
      if (on !== enabled && !on) {
        selectTool("");
        gesture = null;
      }
      enabled = on;
      toolbar.hidden = !on;
    },
    // For tests: each mark as drawn on the last frame (image fractions and canvas
    // pixels), the pointer, and where the frame lies on the canvas.
    drawn() {
      const list = [...marks.values()].map((mark) => {
        const fractions = fractionsOf(mark);
        return { id: mark.id, kind: mark.kind, text: mark.text, anchors: mark.anchors, fractions,
                 pixels: fractions && rect ? fractions.map(toCanvas) : null };
      });
      return { marks: list, pointer: pointer && rect ? toCanvas([pointer.x, pointer.y]) : null,
               rect };
    },
  };
};
