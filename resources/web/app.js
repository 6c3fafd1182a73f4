// Lucent browser client: protocol v1 (docs/protocol.md) over a WebSocket to the
// server that served this page. Plain JavaScript, no build step.
"use strict";

(() => {
  const $ = (id) => document.getElementById(id);
  const ui = {
    status: $("status"), login: $("login"), token: $("token"), connect: $("connect"),
    seriesList: $("series-list"), open: $("open"), preset: $("preset"), mode: $("mode"),
    iso: $("iso"), resetView: $("reset-view"), canvas: $("view"), panel: $("panel"),
    togglePanel: $("toggle-panel"), sessionId: $("session-id"), joinSession: $("join-session"),
    leaveSession: $("leave-session"), sessionInfo: $("session-info"),
  };
  const context = ui.canvas.getContext("2d");

  const kMaxSide = 1024;          // frames asked for are at most this big per side
  const kCameraIntervalMs = 33;   // camera updates at most ~30 a second (server allows 60)
  const kBackoffFirstMs = 500;
  const kBackoffMaxMs = 15000;

  // What the user asked for; restored after a reconnect.
  const view = {
    series: null, azimuth: 0, elevation: 0, zoom: 1, preset: null, mode: "dvr", iso: 300,
    panX: 0, panY: 0, // client-side pan of the shown image, in canvas pixels
  };
  let token = "";
  let socket = null;
  let authenticated = false;
  let opened = false;
  let reconnectTimer = 0;
  let backoffMs = kBackoffFirstMs;
  let stopReconnecting = false;
  let following = null;    // the teaching session followed, or null
  let frame = null;        // the newest decoded frame (ImageBitmap)
  let decoding = false;
  let pendingFrame = null; // a frame that arrived while one was decoding
  let cameraDirty = false;
  let cameraTimer = 0;
  let lastCameraSent = 0;
  let sentSize = "";

  // Read by tests and handy in the console: counters, never secrets.
  const stats = { framesReceived: 0, framesDrawn: 0, lastHeader: null, lastError: null };
  window.lucent = { stats, view };

  function setStatus(text, kind) {
    ui.status.textContent = text;
    ui.status.className = "status" + (kind ? " " + kind : "");
  }

  function send(message) {
    if (socket && socket.readyState === WebSocket.OPEN) {
      socket.send(JSON.stringify(message));
    }
  }

  function enableControls() {
    const live = authenticated;
    ui.seriesList.disabled = !live || following !== null;
    ui.open.disabled = !live || following !== null || ui.seriesList.selectedIndex < 0;
    for (const control of [ui.preset, ui.mode, ui.iso, ui.resetView]) {
      control.disabled = !live || !opened || following !== null;
    }
    ui.joinSession.disabled = !live || following !== null;
    ui.leaveSession.disabled = !live || following === null;
    for (const el of document.querySelectorAll(".iso-only")) {
      el.hidden = view.mode !== "iso";
    }
  }

  // --- connection -----------------------------------------------------------

  function socketUrl() {
    const scheme = location.protocol === "https:" ? "wss:" : "ws:";
    return scheme + "//" + location.host + "/";
  }

  function connect() {
    clearTimeout(reconnectTimer);
    if (socket) {
      socket.onclose = null;
      socket.close();
    }
    stopReconnecting = false;
    authenticated = false;
    opened = false;
    setStatus("connecting to " + location.host + " ...");
    socket = new WebSocket(socketUrl());
    socket.binaryType = "arraybuffer";
    socket.onopen = () => {
      setStatus("authenticating ...");
      send({ type: "auth", token }); // the token goes in the first message, never in the URL
    };
    socket.onmessage = (event) => {
      if (typeof event.data === "string") {
        onText(event.data);
      } else {
        onFrame(event.data);
      }
    };
    socket.onclose = (event) => onClosed(event);
  }

  function onClosed(event) {
    authenticated = false;
    opened = false;
    sentSize = "";
    enableControls();
    if (stopReconnecting) {
      return;
    }
    const seconds = (backoffMs / 1000).toFixed(1);
    const why = event.reason ? " (" + event.reason + ")" : "";
    setStatus("disconnected" + why + "; reconnecting in " + seconds + " s", "bad");
    reconnectTimer = setTimeout(connect, backoffMs * (0.8 + 0.4 * Math.random()));
    backoffMs = Math.min(backoffMs * 2, kBackoffMaxMs);
  }

  function onText(text) {
    let message;
    try {
      message = JSON.parse(text);
    } catch (e) {
      setStatus("the server sent a message that is not JSON", "bad");
      return;
    }
    switch (message.type) {
      case "hello":
        authenticated = true;
        backoffMs = kBackoffFirstMs;
        setStatus("connected (" + message.backend + ")", "good");
        send({ type: "list" });
        if (following) {
          send({ type: "session-join", session: following });
        }
        break;
      case "series":
        showSeries(message.series);
        if (view.series && !following && message.series.some((s) => s.uid === view.series)) {
          openSeries(view.series, true); // a reconnect: back to where the user was
        }
        break;
      case "opened":
        onOpened(message);
        break;
      case "error":
        onError(message);
        break;
      default:
        onSessionMessage(message);
    }
    enableControls();
  }

  function onError(message) {
    stats.lastError = message.code;
    setStatus("error: " + message.message + " [" + message.code + "]", "bad");
    if (message.fatal && message.code.startsWith("auth")) {
      stopReconnecting = true; // a new token is needed, not another try
      ui.token.focus();
    }
  }

  // --- series ---------------------------------------------------------------

  function showSeries(series) {
    const selected = ui.seriesList.value || view.series;
    ui.seriesList.replaceChildren();
    for (const s of series) {
      const option = document.createElement("option");
      option.value = s.uid;
      const dims = Array.isArray(s.dims) ? " " + s.dims.join("x") : "";
      option.textContent = (s.modality || "?") + " " + (s.description || s.uid) + dims;
      ui.seriesList.append(option);
    }
    if (selected) {
      ui.seriesList.value = selected;
    }
    if (ui.seriesList.selectedIndex < 0 && series.length > 0) {
      ui.seriesList.selectedIndex = 0;
    }
  }

  function openSeries(uid, restore) {
    if (!restore) {
      Object.assign(view, { azimuth: 0, elevation: 0, zoom: 1, panX: 0, panY: 0, preset: null });
      view.mode = "dvr";
    }
    view.series = uid;
    sentSize = "";
    send({ type: "open", series: uid });
    setStatus("opening ...");
  }

  function onOpened(message) {
    opened = true;
    view.series = message.series;
    setStatus("showing a " + message.dims.join("x") + " volume", "good");
    sendSize();
    // After a reconnect the server starts from the default view: restore ours.
    if (view.preset && view.preset !== message.preset) {
      send({ type: "tf", preset: view.preset });
    }
    view.preset = view.preset || message.preset;
    ui.preset.value = view.preset;
    if (view.mode !== "dvr") {
      sendMode();
    }
    ui.mode.value = view.mode;
    if (view.azimuth !== 0 || view.elevation !== 0 || view.zoom !== 1) {
      cameraDirty = true;
      flushCamera();
    }
  }

  // --- frames ---------------------------------------------------------------

  function onFrame(buffer) {
    if (buffer.byteLength < 4) {
      return;
    }
    const headerLength = new DataView(buffer).getUint32(0, false); // big-endian
    if (4 + headerLength > buffer.byteLength) {
      return;
    }
    const header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, headerLength)));
    const type = header.format === "png" ? "image/png" : "image/jpeg";
    const blob = new Blob([new Uint8Array(buffer, 4 + headerLength)], { type });
    stats.framesReceived += 1;
    stats.lastHeader = header;
    if (decoding) {
      pendingFrame = blob; // only the newest waiting frame is kept
      return;
    }
    decode(blob);
  }

  function decode(blob) {
    decoding = true;
    createImageBitmap(blob)
      .then((bitmap) => {
        if (frame) {
          frame.close();
        }
        frame = bitmap;
        draw();
        stats.framesDrawn += 1;
      })
      .catch(() => setStatus("a frame could not be decoded", "bad"))
      .finally(() => {
        decoding = false;
        if (pendingFrame) {
          const next = pendingFrame;
          pendingFrame = null;
          decode(next);
        }
      });
  }

  function draw() {
    context.fillStyle = "#000";
    context.fillRect(0, 0, ui.canvas.width, ui.canvas.height);
    if (!frame) {
      return;
    }
    // Interactive frames are smaller than the view: scale them to fit it.
    const scale = Math.min(ui.canvas.width / frame.width, ui.canvas.height / frame.height);
    const w = frame.width * scale;
    const h = frame.height * scale;
    context.imageSmoothingEnabled = true;
    context.drawImage(frame, (ui.canvas.width - w) / 2 + view.panX,
                      (ui.canvas.height - h) / 2 + view.panY, w, h);
  }

  // --- view size ------------------------------------------------------------

  function resizeCanvas() {
    const ratio = window.devicePixelRatio || 1;
    const rect = ui.canvas.getBoundingClientRect();
    const fit = Math.min(1, kMaxSide / Math.max(rect.width * ratio, rect.height * ratio, 1));
    ui.canvas.width = Math.max(16, Math.round(rect.width * ratio * fit));
    ui.canvas.height = Math.max(16, Math.round(rect.height * ratio * fit));
    draw();
    sendSize();
  }

  function sendSize() {
    const size = ui.canvas.width + "x" + ui.canvas.height;
    if (!opened || following || size === sentSize) {
      return;
    }
    sentSize = size;
    send({ type: "size", width: ui.canvas.width, height: ui.canvas.height });
  }

  // --- camera ---------------------------------------------------------------

  function flushCamera() {
    clearTimeout(cameraTimer);
    cameraTimer = 0;
    if (!cameraDirty || !opened || following) {
      return;
    }
    const wait = lastCameraSent + kCameraIntervalMs - performance.now();
    if (wait > 0) {
      cameraTimer = setTimeout(flushCamera, wait);
      return;
    }
    cameraDirty = false;
    lastCameraSent = performance.now();
    send({ type: "camera", azimuth: view.azimuth, elevation: view.elevation, zoom: view.zoom });
  }

  function changeCamera(change) {
    view.azimuth = ((view.azimuth + (change.azimuth || 0)) % 360 + 360) % 360;
    view.elevation = Math.max(-89, Math.min(89, view.elevation + (change.elevation || 0)));
    view.zoom = Math.max(0.02, Math.min(50, view.zoom * (change.zoomFactor || 1)));
    cameraDirty = true;
    if (!cameraTimer) {
      flushCamera();
    }
  }

  function panBy(dx, dy) {
    view.panX += dx;
    view.panY += dy;
    draw();
  }

  // Pointer gestures: one pointer rotates (or pans with the right button or
  // shift), two pointers pinch-zoom and pan. Fine quality returns when they end.
  const pointers = new Map();
  let interacting = false;

  function pixelRatio() {
    return ui.canvas.width / Math.max(1, ui.canvas.getBoundingClientRect().width);
  }

  function startInteraction() {
    if (!interacting && opened && !following) {
      interacting = true;
      send({ type: "quality", quality: "interactive" });
    }
  }

  function endInteraction() {
    if (interacting) {
      interacting = false;
      flushCamera();
      clearTimeout(cameraTimer);
      cameraTimer = 0;
      if (cameraDirty) {
        cameraDirty = false;
        send({ type: "camera", azimuth: view.azimuth, elevation: view.elevation,
               zoom: view.zoom });
      }
      send({ type: "quality", quality: "still" });
    }
  }

  function twoPointerGeometry() {
    const [a, b] = [...pointers.values()];
    return { mx: (a.x + b.x) / 2, my: (a.y + b.y) / 2, distance: Math.hypot(a.x - b.x, a.y - b.y) };
  }

  ui.canvas.addEventListener("pointerdown", (event) => {
    ui.canvas.setPointerCapture(event.pointerId);
    pointers.set(event.pointerId, { x: event.clientX, y: event.clientY,
                                    pan: event.button === 2 || event.shiftKey });
    ui.canvas.classList.add("dragging");
    startInteraction();
    event.preventDefault();
  });

  ui.canvas.addEventListener("pointermove", (event) => {
    const p = pointers.get(event.pointerId);
    if (!p || following) {
      return;
    }
    if (pointers.size >= 2) {
      const before = twoPointerGeometry();
      p.x = event.clientX;
      p.y = event.clientY;
      const after = twoPointerGeometry();
      if (before.distance > 0 && after.distance > 0) {
        changeCamera({ zoomFactor: after.distance / before.distance });
      }
      panBy((after.mx - before.mx) * pixelRatio(), (after.my - before.my) * pixelRatio());
      return;
    }
    const dx = event.clientX - p.x;
    const dy = event.clientY - p.y;
    p.x = event.clientX;
    p.y = event.clientY;
    if (p.pan) {
      panBy(dx * pixelRatio(), dy * pixelRatio());
    } else {
      changeCamera({ azimuth: -dx * 0.4, elevation: dy * 0.4 });
    }
  });

  function pointerGone(event) {
    pointers.delete(event.pointerId);
    if (pointers.size === 0) {
      ui.canvas.classList.remove("dragging");
      endInteraction();
    }
  }
  ui.canvas.addEventListener("pointerup", pointerGone);
  ui.canvas.addEventListener("pointercancel", pointerGone);
  ui.canvas.addEventListener("contextmenu", (event) => event.preventDefault());

  let wheelEndTimer = 0;
  ui.canvas.addEventListener("wheel", (event) => {
    event.preventDefault();
    if (!opened || following) {
      return;
    }
    startInteraction();
    changeCamera({ zoomFactor: Math.exp(-event.deltaY * 0.0015) });
    clearTimeout(wheelEndTimer);
    wheelEndTimer = setTimeout(() => {
      if (pointers.size === 0) {
        endInteraction();
      }
    }, 250);
  }, { passive: false });

  ui.canvas.addEventListener("dblclick", () => resetView());

  function resetView() {
    if (!opened || following) {
      return;
    }
    Object.assign(view, { azimuth: 0, elevation: 0, zoom: 1, panX: 0, panY: 0 });
    cameraDirty = true;
    flushCamera();
    draw();
  }

  // --- rendering choices ----------------------------------------------------

  function sendMode() {
    const message = { type: "mode", mode: view.mode };
    if (view.mode === "iso") {
      message.iso = view.iso;
    }
    send(message);
  }

  ui.preset.addEventListener("change", () => {
    view.preset = ui.preset.value;
    send({ type: "tf", preset: view.preset });
  });
  ui.mode.addEventListener("change", () => {
    view.mode = ui.mode.value;
    sendMode();
    enableControls();
  });
  ui.iso.addEventListener("change", () => {
    const value = Number(ui.iso.value);
    if (Number.isFinite(value)) {
      view.iso = value;
      sendMode();
    }
  });
  ui.resetView.addEventListener("click", resetView);

  // --- teaching sessions (follower) -----------------------------------------

  function onSessionMessage(message) {
    if (message.type === "session-state" && following) {
      ui.sessionInfo.textContent = "following session " + following;
    }
  }

  ui.joinSession.addEventListener("click", () => {
    const id = ui.sessionId.value.trim();
    if (!id) {
      setStatus("enter the session id the presenter gave", "bad");
      return;
    }
    following = id;
    opened = false;
    send({ type: "session-join", session: id });
    ui.sessionInfo.textContent = "joining session " + id + " ...";
    enableControls();
  });
  ui.leaveSession.addEventListener("click", () => {
    send({ type: "session-leave" });
    following = null;
    ui.sessionInfo.textContent = "";
    enableControls();
  });

  // --- page -----------------------------------------------------------------

  ui.login.addEventListener("submit", (event) => {
    event.preventDefault();
    token = ui.token.value;
    backoffMs = kBackoffFirstMs;
    connect();
  });
  ui.seriesList.addEventListener("change", enableControls);
  ui.seriesList.addEventListener("dblclick", () => ui.open.click());
  ui.open.addEventListener("click", () => {
    if (ui.seriesList.value) {
      openSeries(ui.seriesList.value, false);
    }
  });
  ui.togglePanel.addEventListener("click", () => {
    const collapsed = ui.panel.classList.toggle("collapsed");
    ui.togglePanel.setAttribute("aria-expanded", String(!collapsed));
    requestAnimationFrame(resizeCanvas);
  });
  new ResizeObserver(() => resizeCanvas()).observe(ui.canvas);
  window.addEventListener("online", () => {
    if (token && (!socket || socket.readyState === WebSocket.CLOSED) && !stopReconnecting) {
      backoffMs = kBackoffFirstMs;
      connect();
    }
  });
  enableControls();
  resizeCanvas();
})();
