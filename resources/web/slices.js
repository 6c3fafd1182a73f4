// Lucent browser client: the MPR slices (protocol version 4, docs/protocol.md
// "Slices"). Axial, coronal and sagittal views rendered by the server through
// one crosshair point with one window; each arrives as a grey PNG frame whose
// header carries its plane, which turns a click into patient millimetres and
// places the crosshair lines. Wheel: one voxel along the view's normal; click or
// drag: moves the crosshair (all three follow); right drag: window (right =
// wider) and level (down = higher); keys 1-8 on a focused slice: the window
// presets of hello, as the workstation's SliceView. A follower only watches.
"use strict";

window.createLucentSlices = (cells, handlers) => {
  const kViews = ["axial", "coronal", "sagittal"];
  const kSendIntervalMs = 33; // at most ~30 slices messages a second
  const kMaxSide = 1024;      // the protocol allows 2048; a browser cell needs less
  // The controller takes the server's crosshair and window (clamped to the volume, or
  // the default window) only once it has sent nothing for this long: a frame of an
  // older message must not undo a newer scroll.
  const kSettleMs = 300;
  const kColours = { axial: "#4c9aff", coronal: "#6bd68a", sagittal: "#ffb454" };

  const state = { crosshair: null, window: null, presets: [], active: false };
  const stats = { framesReceived: 0, framesDrawn: 0, lastHeader: {} };
  const views = {};
  let enabled = false;
  let dirty = false;
  let sendTimer = 0;
  let lastSent = 0;
  let sentSize = "";
  let settleTimer = 0;
  let newestHeader = null;

  for (const name of kViews) {
    const cell = cells[name];
    const view = {
      name, cell,
      image: cell.querySelector(".slice-image"),
      overlay: cell.querySelector(".slice-overlay"),
      header: null, decoding: false, waiting: null, drag: null,
    };
    views[name] = view;
    bindGestures(view);
  }

  // --- what the page asks the server for ------------------------------------

  function size() {
    const rect = views.axial.cell.getBoundingClientRect();
    const ratio = window.devicePixelRatio || 1;
    const fit = Math.min(1, kMaxSide / Math.max(rect.width * ratio, rect.height * ratio, 1));
    return [Math.max(16, Math.round(rect.width * ratio * fit)),
            Math.max(16, Math.round(rect.height * ratio * fit))];
  }

  function message(all) {
    const m = { type: "slices" };
    if (state.crosshair) {
      m.crosshair = state.crosshair;
    }
    if (state.window) {
      m.window = { center: state.window.center, width: state.window.width };
    }
    const wanted = size();
    if (all || wanted.join("x") !== sentSize) {
      m.size = wanted;
      sentSize = wanted.join("x");
    }
    if (all) {
      m.views = state.active ? kViews : [];
    }
    return m;
  }

  function flush(now) {
    clearTimeout(sendTimer);
    sendTimer = 0;
    if (!dirty || !enabled) {
      return;
    }
    const wait = lastSent + kSendIntervalMs - performance.now();
    if (wait > 0 && !now) {
      sendTimer = setTimeout(flush, wait);
      return;
    }
    dirty = false;
    sendNow(message(false));
  }

  function sendNow(m) {
    lastSent = performance.now();
    handlers.send(m);
    clearTimeout(settleTimer);
    settleTimer = setTimeout(adoptServerState, kSettleMs + 10);
  }

  // The newest frame's crosshair and window become the state: at once for a
  // follower, after kSettleMs without a message for the controller.
  function adoptServerState() {
    const settled = !dirty && !sendTimer && performance.now() - lastSent >= kSettleMs &&
                    !Object.values(views).some((v) => v.drag);
    if (!newestHeader || (enabled && !settled)) {
      return;
    }
    state.crosshair = newestHeader.crosshair;
    state.window = newestHeader.window;
    drawOverlays();
  }

  function changed() {
    dirty = true;
    if (!sendTimer) {
      flush(false);
    }
  }

  // A series opened (its centre starts the crosshair) or the layout changed:
  // the whole state again.
  function restart(centre) {
    if (centre) {
      newestHeader = null;
      state.crosshair = centre.slice();
      state.window = null; // the server starts from the volume's default window
    }
    if (!enabled || !state.active) {
      return;
    }
    sentSize = "";
    dirty = false;
    sendNow(message(true));
  }

  function setWindow(center, width) {
    state.window = { center, width: Math.max(0, width) };
    changed();
  }

  function applyPreset(name) {
    const preset = state.presets.find((p) => p.name === name);
    if (preset && enabled) {
      state.window = { center: preset.center, width: preset.width };
      dirty = false;
      sendNow(Object.assign(message(false), { window: preset.name }));
    }
  }

  // --- frames ----------------------------------------------------------------

  // A binary frame whose header names a slice view: drawn here (true); any other: false.
  function takeFrame(buffer) {
    if (buffer.byteLength < 4) {
      return false;
    }
    const length = new DataView(buffer).getUint32(0, false);
    if (4 + length > buffer.byteLength) {
      return false;
    }
    let header;
    try {
      header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, length)));
    } catch (e) {
      return false;
    }
    const view = views[header.view];
    if (!view) {
      return false;
    }
    stats.framesReceived += 1;
    const item = { header, blob: new Blob([new Uint8Array(buffer, 4 + length)],
                                          { type: "image/png" }) };
    if (view.decoding) {
      view.waiting = item; // only the newest waiting frame is kept
    } else {
      decode(view, item);
    }
    handlers.onFrame(header);
    return true;
  }

  function decode(view, item) {
    view.decoding = true;
    createImageBitmap(item.blob)
      .then((bitmap) => {
        view.image.width = bitmap.width;
        view.image.height = bitmap.height;
        view.image.getContext("2d").drawImage(bitmap, 0, 0);
        bitmap.close();
        view.header = item.header;
        if (!newestHeader || item.header.seq >= newestHeader.seq) {
          newestHeader = item.header;
        }
        stats.lastHeader[view.name] = item.header;
        stats.framesDrawn += 1;
        adoptServerState();
        drawOverlays();
      })
      .catch(() => handlers.onError("a slice could not be decoded"))
      .finally(() => {
        view.decoding = false;
        if (view.waiting) {
          const next = view.waiting;
          view.waiting = null;
          decode(view, next);
        }
      });
  }

  // --- plane geometry --------------------------------------------------------

  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                           a[0] * b[1] - a[1] * b[0]];

  // Image pixel (x, y) of a frame to LPS mm, and back.
  function pointAt(header, x, y) {
    const p = header.plane;
    const dx = (x - (header.width - 1) / 2) * p.pixel_mm;
    const dy = (y - (header.height - 1) / 2) * p.pixel_mm;
    return [0, 1, 2].map((a) => p.centre[a] + p.u[a] * dx + p.v[a] * dy);
  }

  function pixelOf(header, point) {
    const p = header.plane;
    const d = [0, 1, 2].map((a) => point[a] - p.centre[a]);
    return [dot(d, p.u) / p.pixel_mm + (header.width - 1) / 2,
            dot(d, p.v) / p.pixel_mm + (header.height - 1) / 2];
  }

  // The image pixel under a pointer event on the view's canvas.
  function imagePixel(view, event) {
    const rect = view.image.getBoundingClientRect();
    return [(event.clientX - rect.left) * view.image.width / Math.max(1, rect.width) - 0.5,
            (event.clientY - rect.top) * view.image.height / Math.max(1, rect.height) - 0.5];
  }

  // The crosshair lines: where the other two planes cut this one.
  function drawOverlays() {
    for (const view of Object.values(views)) {
      const g = view.overlay.getContext("2d");
      view.overlay.width = view.image.width;
      view.overlay.height = view.image.height;
      g.clearRect(0, 0, view.overlay.width, view.overlay.height);
      if (!view.header || !state.crosshair) {
        continue;
      }
      const [x, y] = pixelOf(view.header, state.crosshair);
      const lines = { axial: ["sagittal", "coronal"], coronal: ["sagittal", "axial"],
                      sagittal: ["coronal", "axial"] }[view.name];
      g.lineWidth = Math.max(1, Math.round((window.devicePixelRatio || 1)));
      g.strokeStyle = kColours[lines[0]];
      g.beginPath();
      g.moveTo(x + 0.5, 0);
      g.lineTo(x + 0.5, view.overlay.height);
      g.stroke();
      g.strokeStyle = kColours[lines[1]];
      g.beginPath();
      g.moveTo(0, y + 0.5);
      g.lineTo(view.overlay.width, y + 0.5);
      g.stroke();
    }
  }

  // --- gestures --------------------------------------------------------------

  function moveCrosshair(view, event) {
    if (!view.header) {
      return;
    }
    const [x, y] = imagePixel(view, event);
    state.crosshair = pointAt(view.header, x, y);
    drawOverlays();
    changed();
  }

  function bindGestures(view) {
    const target = view.overlay;
    target.addEventListener("contextmenu", (event) => event.preventDefault());
    target.addEventListener("pointerdown", (event) => {
      if (!enabled) {
        return;
      }
      target.focus();
      target.setPointerCapture(event.pointerId);
      if (event.button === 2) {
        const w = state.window || { center: 40, width: 400 };
        view.drag = { kind: "window", x: event.clientX, y: event.clientY,
                      center: w.center, width: w.width };
      } else if (event.button === 0) {
        view.drag = { kind: "crosshair" };
        moveCrosshair(view, event);
      }
      event.preventDefault();
    });
    target.addEventListener("pointermove", (event) => {
      if (!enabled || !view.drag) {
        return;
      }
      if (view.drag.kind === "crosshair") {
        moveCrosshair(view, event);
      } else {
        // One unit a pixel, as the workstation's CT window (right = wider, down = higher).
        const step = 1;
        setWindow(view.drag.center + (event.clientY - view.drag.y) * step,
                  view.drag.width + (event.clientX - view.drag.x) * step);
      }
    });
    const end = () => {
      if (view.drag) {
        view.drag = null;
        flush(true);
      }
    };
    target.addEventListener("pointerup", end);
    target.addEventListener("pointercancel", end);
    target.addEventListener("wheel", (event) => {
      event.preventDefault();
      if (!enabled || !view.header || !state.crosshair || event.deltaY === 0) {
        return;
      }
      // One voxel a notch along the normal; forward (deltaY < 0) goes deeper.
      const p = view.header.plane;
      const n = cross(p.u, p.v);
      const notches = event.deltaY < 0 ? 1 : -1;
      state.crosshair = state.crosshair.map((c, a) => c + n[a] * p.step_mm * notches);
      drawOverlays();
      changed();
    }, { passive: false });
    target.addEventListener("keydown", (event) => {
      const index = Number(event.key) - 1;
      if (enabled && Number.isInteger(index) && index >= 0 && index < state.presets.length) {
        applyPreset(state.presets[index].name);
        event.preventDefault();
      }
    });
  }

  new ResizeObserver(() => {
    if (enabled && state.active) {
      changed();
    }
  }).observe(views.axial.cell);

  return {
    stats, state, takeFrame, restart, applyPreset,
    setPresets(presets) { state.presets = Array.isArray(presets) ? presets : []; },
    // Whether the slice views are shown (the layout); the server renders only then.
    setActive(active) {
      state.active = active;
      if (active) {
        restart(null);
      } else if (enabled) {
        sendNow({ type: "slices", views: [] });
      }
    },
    // Gestures and messages only while the user controls the view.
    setEnabled(on) {
      enabled = on;
      if (!on) {
        for (const view of Object.values(views)) {
          view.drag = null;
        }
      }
    },
    pixelOf, pointAt,
  };
};
