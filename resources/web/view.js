// Lucent browser client: the canvas. Decodes and draws frames (newest wins),
// sizes the canvas to its box, and turns mouse and touch gestures (pointer
// events) into camera changes: one pointer rotates, right button or shift
// pans, the wheel and two-finger pinches zoom, two fingers also pan; arrow
// keys rotate and + and - zoom. A pan is a camera change in canvas pixels
// (panX right, panY down) that the page turns into the camera's pan in mm.
"use strict";

window.createLucentView = (canvas, handlers) => {
  const context = canvas.getContext("2d");
  const kMaxSide = 1024; // frames asked for are at most this big per side
  const kDegreesPerPixel = 0.4;

  let frame = null;        // the newest decoded frame (ImageBitmap)
  let decoding = false;
  let waiting = null;      // the newest frame that arrived while one was decoding
  let enabled = false;
  const stats = { framesReceived: 0, framesDrawn: 0, lastHeader: null };

  function draw() {
    context.fillStyle = "#000";
    context.fillRect(0, 0, canvas.width, canvas.height);
    if (!frame) {
      return;
    }
    // Interactive frames are smaller than the view: scale them to fit it.
    const scale = Math.min(canvas.width / frame.width, canvas.height / frame.height);
    const w = frame.width * scale;
    const h = frame.height * scale;
    context.imageSmoothingEnabled = true;
    const x = (canvas.width - w) / 2;
    const y = (canvas.height - h) / 2;
    context.drawImage(frame, x, y, w, h);
    handlers.onOverlay(context, { x, y, w, h }, stats.lastHeader); // the pointer and marks
  }

  function decode(item) {
    decoding = true;
    createImageBitmap(item.blob)
      .then((bitmap) => {
        if (frame) {
          frame.close();
        }
        frame = bitmap;
        stats.lastHeader = item.header;
        draw();
        stats.framesDrawn += 1;
      })
      .catch(() => handlers.onError("a frame could not be decoded"))
      .finally(() => {
        decoding = false;
        if (waiting) {
          const next = waiting;
          waiting = null;
          decode(next);
        }
      });
  }

  // A binary frame: 4 bytes big-endian header length N, N bytes of JSON, the image.
  function showFrame(buffer) {
    if (buffer.byteLength < 4) {
      return false;
    }
    const headerLength = new DataView(buffer).getUint32(0, false);
    if (4 + headerLength > buffer.byteLength) {
      return false;
    }
    let header;
    try {
      header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, headerLength)));
    } catch (e) {
      return false;
    }
    const type = header.format === "png" ? "image/png" : "image/jpeg";
    const item = { header, blob: new Blob([new Uint8Array(buffer, 4 + headerLength)], { type }) };
    stats.framesReceived += 1;
    if (decoding) {
      waiting = item; // only the newest waiting frame is kept
    } else {
      decode(item);
    }
    return true;
  }

  function resize() {
    const ratio = window.devicePixelRatio || 1;
    const rect = canvas.getBoundingClientRect();
    const fit = Math.min(1, kMaxSide / Math.max(rect.width * ratio, rect.height * ratio, 1));
    canvas.width = Math.max(16, Math.round(rect.width * ratio * fit));
    canvas.height = Math.max(16, Math.round(rect.height * ratio * fit));
    draw();
    handlers.onResize(canvas.width, canvas.height);
  }

  function panBy(dx, dy) {
    if (dx !== 0 || dy !== 0) {
      handlers.onCamera({ panX: dx, panY: dy });
    }
  }

  // --- gestures -------------------------------------------------------------

  const pointers = new Map();
  let interacting = false;
  let wheelEndTimer = 0;

  function pixelRatio() {
    return canvas.width / Math.max(1, canvas.getBoundingClientRect().width);
  }
  function startInteraction() {
    if (!interacting) {
      interacting = true;
      handlers.onInteraction(true);
    }
  }
  function endInteraction() {
    if (interacting) {
      interacting = false;
      handlers.onInteraction(false);
    }
  }
  function twoPointers() {
    const [a, b] = [...pointers.values()];
    return { x: (a.x + b.x) / 2, y: (a.y + b.y) / 2, gap: Math.hypot(a.x - b.x, a.y - b.y) };
  }

  canvas.addEventListener("pointerdown", (event) => {
    if (!enabled) {
      return;
    }
    canvas.setPointerCapture(event.pointerId);
    pointers.set(event.pointerId, { x: event.clientX, y: event.clientY,
                                    pan: event.button === 2 || event.shiftKey });
    canvas.classList.add("dragging");
    startInteraction();
    event.preventDefault();
  });

  canvas.addEventListener("pointermove", (event) => {
    const p = pointers.get(event.pointerId);
    if (!p || !enabled) {
      return;
    }
    if (pointers.size >= 2) {
      const before = twoPointers();
      p.x = event.clientX;
      p.y = event.clientY;
      const after = twoPointers();
      if (before.gap > 0 && after.gap > 0) {
        handlers.onCamera({ zoomFactor: after.gap / before.gap });
      }
      panBy((after.x - before.x) * pixelRatio(), (after.y - before.y) * pixelRatio());
      return;
    }
    const dx = event.clientX - p.x;
    const dy = event.clientY - p.y;
    p.x = event.clientX;
    p.y = event.clientY;
    if (p.pan) {
      panBy(dx * pixelRatio(), dy * pixelRatio());
    } else {
      handlers.onCamera({ azimuth: -dx * kDegreesPerPixel, elevation: dy * kDegreesPerPixel });
    }
  });

  function pointerGone(event) {
    pointers.delete(event.pointerId);
    if (pointers.size === 0) {
      canvas.classList.remove("dragging");
      endInteraction();
    }
  }
  canvas.addEventListener("pointerup", pointerGone);
  canvas.addEventListener("pointercancel", pointerGone);
  canvas.addEventListener("contextmenu", (event) => event.preventDefault());

  canvas.addEventListener("wheel", (event) => {
    event.preventDefault();
    if (!enabled) {
      return;
    }
    startInteraction();
    handlers.onCamera({ zoomFactor: Math.exp(-event.deltaY * 0.0015) });
    clearTimeout(wheelEndTimer);
    wheelEndTimer = setTimeout(() => {
      if (pointers.size === 0) {
        endInteraction();
      }
    }, 250);
  }, { passive: false });

  // Keys on the focused canvas: arrows rotate, + and - zoom, 0 resets.
  const kKeySteps = {
    ArrowLeft: { azimuth: 5 }, ArrowRight: { azimuth: -5 },
    ArrowUp: { elevation: -5 }, ArrowDown: { elevation: 5 },
    "+": { zoomFactor: 1.1 }, "=": { zoomFactor: 1.1 }, "-": { zoomFactor: 1 / 1.1 },
  };
  canvas.addEventListener("keydown", (event) => {
    if (!enabled) {
      return;
    }
    if (event.key === "0") {
      handlers.onReset();
    } else if (kKeySteps[event.key]) {
      handlers.onCamera(kKeySteps[event.key]);
    } else {
      return;
    }
    event.preventDefault();
  });

  canvas.addEventListener("dblclick", () => {
    if (enabled) {
      handlers.onReset();
    }
  });

  new ResizeObserver(() => resize()).observe(canvas);

  return {
    stats,
    showFrame,
    resize,
    size: () => ({ width: canvas.width, height: canvas.height }),
    redraw: draw,
    // Gestures act only while the user controls the view.
    setEnabled(on) {
      enabled = on;
      if (!on) {
        pointers.clear();
        canvas.classList.remove("dragging");
        interacting = false;
      }
    },
  };
};
