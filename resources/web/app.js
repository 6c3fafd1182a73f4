// Lucent browser client: protocol version 4 (docs/protocol.md; it sends no
// sampling message, and invites need version 3) over a WebSocket to the server
// that served this page: the wiring. Here: authentication by token or by a join
// link's invite, series, view changes and who controls the view. The connection
// and its reconnect live in connection.js, teaching sessions and their invites in
// sessions.js, the canvas in view.js. Plain JavaScript, no build step.
"use strict";

(() => {
  const $ = (id) => document.getElementById(id);
  const ui = {
    status: $("status"), login: $("login"), token: $("token"), seriesList: $("series-list"),
    open: $("open"), preset: $("preset"), mode: $("mode"), iso: $("iso"),
    resetView: $("reset-view"), panel: $("panel"), togglePanel: $("toggle-panel"),
    viewport: $("viewport"), layout: $("layout"), windowPreset: $("window-preset"),
  };

  const kCameraIntervalMs = 33; // at most ~30 camera updates a second (the server allows 60)

  // What the user asked for; restored after a reconnect.
  const view = { series: null, azimuth: 0, elevation: 0, zoom: 1, panRight: 0, panUp: 0,
                 radius: 0, preset: null, mode: "dvr",
                 iso: 300 };
  // A join link's invite: this page then only follows that session.
  const invite = takeInviteFromAddress();
  let authenticated = false;
  let opened = false;
  let restoring = false;        // the next `opened` reopens the view the user had
  let cameraDirty = false;
  let cameraTimer = 0;
  let lastCameraSent = 0;
  let sentSize = "";
  let protocolVersion = 0;      // the connection's, from hello

  const connection = window.createLucentConnection(invite, {
    setStatus, onConnecting, onText, onBinary, onClosed,
  });
  const send = connection.send;
  // Joining, presenting and following a session, and the presenter's invites (sessions.js).
  const sessions = window.createLucentSessions(invite, {
    send, setStatus, updateControls,
    onJoining: () => {
      opened = false;
    },
    onRole: (role) => freeLook.setRole(protocolVersion >= 4 ? role : null),
    onLeft: () => {
      freeLook.setRole(null);
      opened = false;
    },
    stopReconnecting: () => connection.stopReconnecting(),
  });

  let gesture = false;           // a drag or wheel is under way on the canvas
  const canvasView = window.createLucentView($("view"), {
    onCamera: changeCamera,
    onInteraction: (active) => {
      gesture = active;
      if (!steering()) {
        lookAround(); // a follower's gesture: free look (freelook.js)
        return;
      }
      if (!active) {
        flushCamera(true);
      }
      send({ type: "interaction", state: active ? "start" : "end" });
    },
    onResize: () => sendSize(),
    onReset: () => resetView(),
    onError: (text) => setStatus(text, "bad"),
    onOverlay: (context, rect, header) => marks.draw(context, rect, header),
  });
  // The presenter's pointer and marks over the frame (marks.js).
  const marks = window.createLucentMarks($("view"), canvasView, {
    send, toolbar: $("mark-tools"), textInput: $("mark-text"),
  });
  const freeLook = window.createLucentFreeLook(
    { back: $("back-to-teacher"), recall: $("recall-free-look"), info: $("free-look-info") },
    { send, onStarted: startSteering, onEnded: stopSteering });
  // MPR slices (version 4): slices.js; the layout and the window picker here.
  const sliceViews = window.createLucentSlices(
    { axial: $("slice-axial"), coronal: $("slice-coronal"), sagittal: $("slice-sagittal") },
    { send,
      onFrame: (header) => {
        if (ui.layout.value === "3d" && !controlling()) {
          setLayout("both"); // a follower sees the presenter's slices
        }
        const preset = sliceViews.state.presets.find(
          (p) => p.center === header.window.center && p.width === header.window.width);
        ui.windowPreset.value = preset ? preset.name : "";
      },
      onError: (text) => setStatus(text, "bad") });

  function setLayout(layout) {
    ui.layout.value = layout;
    ui.viewport.className = "viewport layout-" + layout;
    sliceViews.setActive(layout !== "3d");
    requestAnimationFrame(() => canvasView.resize());
  }

  // After a replay the view goes on from the recording's last camera, at this page's size.
  const recordings = window.createLucentRecordings({ send, onReplayEnded: (message) => {
    const c = message.camera || {};
    Object.assign(view, { azimuth: c.azimuth ?? view.azimuth, elevation: c.elevation ?? view.elevation,
                          zoom: c.zoom ?? view.zoom, panRight: c.pan_right ?? view.panRight,
                          panUp: c.pan_up ?? view.panUp });
    sentSize = "";
    sendSize();
  } });
  // Read by tests and handy in the console: counters and the view, never the token.
  window.lucent = { stats: canvasView.stats, view, session: sessions.session,
                    slices: sliceViews, setLayout, freeLook: () => freeLook.active(),
                    protocolVersion: () => protocolVersion, invited: () => invite !== "",
                    shownInvite: sessions.shownInvite, marks: () => marks.drawn(),
                    recordings: () => recordings.state() };

  // https://host:port/#invite=CODE: the code rides in the fragment, which no
  // request and no Referer carries; it is taken out of the address bar at once
  // (and so out of the history and any screenshot of the page).
  function takeInviteFromAddress() {
    const match = /^#invite=([A-Za-z0-9_-]{16,128})$/.exec(location.hash);
    if (!match) {
      return "";
    }
    history.replaceState(null, "", location.pathname + location.search);
    return match[1];
  }

  // Never while joining: a page that joins a session follows it until told otherwise.
  function controlling() {
    const session = sessions.session();
    return authenticated && opened && !sessions.joining() &&
           (!session || session.role === "presenter");
  }

  // The camera and size this page sends: its own view, the session's as its
  // presenter, or its own view in a session while in free look.
  function steering() {
    return controlling() || (authenticated && opened && freeLook.active());
  }

  // A follower of a version 4 server may look around on its own.
  function lookAround() {
    const session = sessions.session();
    if (authenticated && opened && session && session.role === "follower" &&
        protocolVersion >= 4) {
      freeLook.request();
    }
  }

  function startSteering(camera) {
    Object.assign(view, { azimuth: camera.azimuth || 0, elevation: camera.elevation || 0,
                          zoom: camera.zoom || 1, panRight: camera.pan_right || 0,
                          panUp: camera.pan_up || 0 });
    sentSize = "";
    sendSize();
    if (gesture) {
      send({ type: "interaction", state: "start" });
    }
    setStatus("looking on your own: \"Back to teacher\" follows the presenter again", "good");
    updateControls();
  }

  function stopSteering(why) {
    cameraDirty = false;
    setStatus(why, "good");
    updateControls();
  }

  function setStatus(text, kind) {
    ui.status.textContent = text;
    ui.status.className = "status" + (kind ? " " + kind : "");
  }

  function updateControls() {
    const session = sessions.session();
    const following = session !== null && session.role === "follower";
    ui.seriesList.disabled = !authenticated || following;
    ui.open.disabled = ui.seriesList.disabled || ui.seriesList.selectedIndex < 0;
    for (const control of [ui.preset, ui.mode, ui.iso, ui.resetView]) {
      control.disabled = !controlling();
    }
    sessions.updateControls(authenticated, protocolVersion);
    for (const el of document.querySelectorAll(".iso-only")) {
      el.hidden = view.mode !== "iso";
    }
    canvasView.setEnabled(controlling() || (following && opened && protocolVersion >= 4));
    marks.setEnabled(controlling() && protocolVersion >= 4);
    ui.layout.disabled = protocolVersion < 4 || !opened;
    ui.windowPreset.disabled = protocolVersion < 4 || !controlling();
    sliceViews.setEnabled(protocolVersion >= 4 && controlling());
    recordings.update({ present: controlling() && protocolVersion >= 4,
                        list: authenticated && !invite && protocolVersion >= 4 });
  }

  // --- connection -----------------------------------------------------------

  function onConnecting() {
    authenticated = false;
    opened = false;
  }

  function onBinary(data) {
    if (!sliceViews.takeFrame(data) && !canvasView.showFrame(data)) {
      setStatus("the server sent a frame that is not readable", "bad");
    }
  }

  // The connection is gone (connection.js then tries again, or not).
  function onClosed() {
    freeLook.setRole(null);
    authenticated = false;
    opened = false;
    sentSize = "";
    sessions.disconnected();
    recordings.reset(); // the server stored what was recorded; a replay ended with the socket
    updateControls();
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
        protocolVersion = message.version;
        showWindowPresets(message.window_presets || []);
        connection.authenticated();
        setStatus("connected (" + message.backend + ")", "good");
        if (invite) {
          sessions.joinByInvite(); // the invite joins its session by itself
          setStatus("joining the session ...", "good");
          break;
        }
        send({ type: "list" });
        if (protocolVersion >= 4) {
          recordings.list();
        }
        sessions.rejoin(); // a follower comes back to its session
        break;
      case "series":
        showSeries(message.series);
        if (view.series && !sessions.session() && !opened &&
            message.series.some((s) => s.uid === view.series)) {
          openSeries(view.series, true); // a reconnect: back to where the user was
        }
        break;
      case "opened":
        marks.reset();
        onOpened(message);
        break;
      case "pointer":
      case "mark":
      case "marks-cleared":
        marks.handle(message);
        break;
      case "session-left":
        marks.reset();
        sessions.onMessage(message);
        break;
      case "error":
        onError(message);
        break;
      default:
        if (!freeLook.onMessage(message) && !recordings.onMessage(message)) {
          sessions.onMessage(message);
        }
    }
    updateControls();
  }

  function onError(message) {
    setStatus("error: " + message.message + " [" + message.code + "]", "bad");
    freeLook.refused(message);
    sessions.refused(message);
    if (message.fatal && message.code.startsWith("auth")) {
      connection.stopReconnecting(); // a new token (or invite) is needed, not another try
      if (invite) {
        setStatus(message.message + ": ask the presenter for a new link", "bad");
      } else {
        ui.token.focus();
      }
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
    restoring = restore;
    view.series = uid;
    send({ type: "open", series: uid });
    setStatus("opening ...");
  }

  function showPanel(shown) {
    ui.panel.classList.toggle("collapsed", !shown);
    ui.togglePanel.setAttribute("aria-expanded", String(shown));
    requestAnimationFrame(() => canvasView.resize());
  }

  function onOpened(message) {
    opened = true;
    if (window.matchMedia("(max-width: 700px)").matches) {
      showPanel(false); // a phone: the view gets the screen; "Controls" brings the panel back
    }
    sentSize = "";
    view.series = message.series;
    view.radius = message.radius_mm || 0;
    setStatus("showing a " + message.dims.join("x") + " volume", "good");
    if (!controlling() || recordings.replaying()) { // a follower sees what the presenter chose,
      ui.preset.value = message.preset;             // a replay what the recording holds
      return;
    }
    sendSize();
    if (restoring) {
      // After a reconnect the server starts from the default view: restore ours.
      if (view.preset && view.preset !== message.preset) {
        send({ type: "tf", preset: view.preset });
      }
      if (view.mode !== "dvr") {
        sendMode();
      }
      if (view.azimuth !== 0 || view.elevation !== 0 || view.zoom !== 1 ||
          view.panRight !== 0 || view.panUp !== 0) {
        cameraDirty = true;
        flushCamera(true);
      }
      view.preset = view.preset || message.preset;
    } else {
      Object.assign(view, { azimuth: 0, elevation: 0, zoom: 1, panRight: 0, panUp: 0,
                            mode: "dvr", preset: message.preset });
    }
    const restored = restoring;
    restoring = false;
    ui.preset.value = view.preset;
    ui.mode.value = view.mode;
    updateControls();
    // After a reconnect the slices' crosshair and window are the user's, sent again.
    sliceViews.restart(restored && sliceViews.state.crosshair ? null : message.centre || null);
  }

  function showWindowPresets(presets) {
    sliceViews.setPresets(presets);
    ui.windowPreset.replaceChildren(new Option("custom", ""));
    presets.forEach((p, i) => {
      ui.windowPreset.append(new Option((i + 1) + " " + p.name + " (" + p.center + "/" +
                                        p.width + ")", p.name));
    });
  }

  function sendSize() {
    const { width, height } = canvasView.size();
    const size = width + "x" + height;
    if (!steering() || recordings.replaying() || size === sentSize) {
      return;
    }
    sentSize = size;
    send({ type: "size", width, height });
  }

  // --- camera and rendering choices -----------------------------------------

  function flushCamera(now) {
    clearTimeout(cameraTimer);
    cameraTimer = 0;
    if (!cameraDirty || !steering()) {
      return;
    }
    const wait = lastCameraSent + kCameraIntervalMs - performance.now();
    if (wait > 0 && !now) {
      cameraTimer = setTimeout(flushCamera, wait);
      return;
    }
    cameraDirty = false;
    lastCameraSent = performance.now();
    send({ type: "camera", azimuth: view.azimuth, elevation: view.elevation, zoom: view.zoom,
           pan_right: view.panRight, pan_up: view.panUp });
  }

  // Millimetres per canvas pixel in the plane of the point looked at: the
  // server's camera fits the volume's bounding sphere (radius_mm of `opened`)
  // into the narrower side of a 30 degree view, zoom narrows the view.
  function mmPerPixel() {
    const { width, height } = canvasView.size();
    const halfFov = 15 * Math.PI / 180;
    const fitHalf = Math.min(halfFov, Math.atan(Math.tan(halfFov) * width / Math.max(1, height)));
    const distance = (view.radius || 100) / Math.sin(fitHalf);
    return 2 * distance * Math.tan(halfFov) / view.zoom / Math.max(1, height);
  }

  function changeCamera(change) {
    if (!steering()) {
      lookAround(); // free look starts from the session's camera, not from here
      return;
    }
    view.azimuth = ((view.azimuth + (change.azimuth || 0)) % 360 + 360) % 360;
    view.elevation = Math.max(-89, Math.min(89, view.elevation + (change.elevation || 0)));
    view.zoom = Math.max(0.02, Math.min(50, view.zoom * (change.zoomFactor || 1)));
    if (change.panX || change.panY) {
      // The image follows the pointer: the point looked at moves the other way.
      const mm = mmPerPixel();
      const limit = 100000; // the protocol's bound
      view.panRight = Math.max(-limit, Math.min(limit, view.panRight - (change.panX || 0) * mm));
      view.panUp = Math.max(-limit, Math.min(limit, view.panUp + (change.panY || 0) * mm));
    }
    cameraDirty = true;
    if (!cameraTimer) {
      flushCamera(false);
    }
  }

  function resetView() {
    Object.assign(view, { azimuth: 0, elevation: 0, zoom: 1, panRight: 0, panUp: 0 });
    cameraDirty = true;
    flushCamera(true);
  }

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
    updateControls();
  });
  ui.iso.addEventListener("change", () => {
    const value = Number(ui.iso.value);
    if (Number.isFinite(value)) {
      view.iso = value;
      sendMode();
    }
  });
  ui.resetView.addEventListener("click", resetView);
  ui.layout.addEventListener("change", () => setLayout(ui.layout.value));
  ui.windowPreset.addEventListener("change", () => {
    if (ui.windowPreset.value) {
      sliceViews.applyPreset(ui.windowPreset.value);
    }
  });

  // --- page -----------------------------------------------------------------

  ui.login.addEventListener("submit", (event) => {
    event.preventDefault();
    connection.start(ui.token.value);
  });
  ui.seriesList.addEventListener("change", updateControls);
  ui.seriesList.addEventListener("dblclick", () => ui.open.click());
  ui.open.addEventListener("click", () => {
    if (ui.seriesList.value) {
      openSeries(ui.seriesList.value, false);
    }
  });
  ui.togglePanel.addEventListener("click", () => {
    showPanel(ui.panel.classList.contains("collapsed"));
  });
  if (invite) {
    // A student with a join link: only the view, following the presenter.
    document.body.classList.add("invited");
    showPanel(false);
    connection.start("");
  }
  updateControls();
  canvasView.resize();
})();
