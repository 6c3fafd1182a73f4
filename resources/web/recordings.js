// Lucent browser client: recording and replay (protocol version 4,
// docs/protocol.md "Recording and replay"). The presenter's Record / Stop
// button, the store's recordings with Play (the original pace) and Step (one
// recorded view a click), and the replay's progress. app.js passes it the
// server's messages and says who may do what. Plain JavaScript, no build step.
"use strict";

window.createLucentRecordings = (options) => {
  const $ = (id) => document.getElementById(id);
  const ui = {
    group: $("recording-group"), record: $("record"), info: $("recording-info"),
    list: $("recording-list"), refresh: $("refresh-recordings"), play: $("play-recording"),
    step: $("step-recording"), stop: $("stop-replay"),
  };
  const send = options.send;
  let allowed = { present: false, list: false };
  let recording = null; // the id while this client records
  let replay = null;    // {id, pace, view, views} while one runs

  function minutes(ms) {
    const s = Math.round(ms / 1000);
    return Math.floor(s / 60) + ":" + String(s % 60).padStart(2, "0");
  }

  function showList(recordings) {
    const selected = ui.list.value;
    ui.list.textContent = "";
    for (const r of recordings) {
      const option = document.createElement("option");
      option.value = r.id;
      option.textContent = new Date(r.created).toLocaleString() + " - " + minutes(r.duration_ms) +
        ", " + r.views + " views";
      option.selected = r.id === selected;
      ui.list.appendChild(option);
    }
  }

  function update(state) {
    allowed = state;
    ui.group.hidden = !state.list;
    ui.record.disabled = !state.present || replay !== null;
    ui.record.textContent = recording ? "Stop recording" : "Record";
    ui.record.classList.toggle("recording", recording !== null);
    ui.list.disabled = !state.list;
    ui.refresh.disabled = !state.list;
    // One replay at a time: Stop replay before another (the page sends no view
    // message while one runs, and would not tell the two replays' ends apart).
    const chosen = ui.list.selectedIndex >= 0;
    const canStart = state.present && recording === null && chosen && replay === null;
    ui.play.disabled = !canStart;
    ui.step.disabled = !canStart && !(state.present && replay && replay.pace === "step");
    ui.stop.disabled = replay === null;
  }

  function replayStatus() {
    if (!replay) {
      return;
    }
    ui.info.textContent = (replay.pace === "step" ? "stepping" : "playing") + " view " +
      (replay.view + 1) + " of " + replay.views;
  }

  // True when the message was one of these.
  function onMessage(message) {
    switch (message.type) {
      case "recording-started":
        recording = message.recording;
        ui.info.textContent = "recording ...";
        break;
      case "recording-stopped":
        recording = null;
        ui.info.textContent = "recorded " + message.views + " views in " +
          minutes(message.duration_ms) + (message.reason === "stopped" ? "" : " (" +
          message.reason + ")");
        send({ type: "recording-list" });
        break;
      case "recordings":
        showList(message.recordings);
        break;
      case "replay-progress":
        replay = { id: message.recording, pace: replay ? replay.pace : "original",
                   view: message.view, views: message.views };
        replayStatus();
        break;
      case "replay-ended":
        replay = null;
        ui.info.textContent = message.reason === "end" ? "replay finished" : "replay stopped";
        if (options.onReplayEnded) {
          options.onReplayEnded(message);
        }
        break;
      default:
        return false;
    }
    update(allowed);
    return true;
  }

  // The connection is gone: nothing records or replays any more.
  function reset() {
    recording = null;
    replay = null;
    update(allowed);
  }

  function startReplay(pace) {
    if (!ui.list.value) {
      return;
    }
    replay = { id: ui.list.value, pace, view: 0, views: 0 };
    send({ type: "replay", recording: ui.list.value, pace });
    update(allowed);
  }

  ui.record.addEventListener("click", () => {
    send({ type: "record", state: recording ? "stop" : "start" });
  });
  ui.refresh.addEventListener("click", () => send({ type: "recording-list" }));
  ui.list.addEventListener("change", () => update(allowed));
  ui.play.addEventListener("click", () => startReplay("original"));
  ui.step.addEventListener("click", () => {
    if (replay && replay.pace === "step") {
      send({ type: "replay-step" });
    } else {
      startReplay("step");
    }
  });
  ui.stop.addEventListener("click", () => send({ type: "replay-stop" }));

  // While a replay runs the page sends no view message of its own (size
  // included): the server would end the replay, as when the presenter takes
  // the view back. Frames of the recorded size are scaled to the canvas.
  return { onMessage, update, reset, list: () => send({ type: "recording-list" }),
           replaying: () => replay !== null,
           state: () => ({ recording, replay }) };
};
