// Lucent browser client: free look (protocol version 4, docs/protocol.md "Free
// look"). A follower's drag or wheel asks the server for its own view (the page
// then steers that view's camera); "Back to teacher" snaps back to the session's
// view. The presenter sees how many followers look on their own and can bring
// everyone back. The page (app.js) sends and routes the messages.
"use strict";

window.createLucentFreeLook = (elements, handlers) => {
  // off: following the session; asked: free-look start sent; on: own view.
  let state = "off";
  let looking = 0;
  let presenting = false;
  // What a follower is told when free look ends, by its reason.
  const kEnded = {
    recalled: "following the presenter (the presenter called everyone back)",
    series: "following the presenter (the presenter opened another series)",
    presenting: "you present now",
  };

  function update() {
    elements.back.hidden = state === "off";
    elements.recall.hidden = !presenting;
    elements.recall.disabled = !presenting || looking === 0;
    elements.info.hidden = !presenting;
    elements.info.textContent = looking === 1 ? "1 follower looks on their own"
      : looking + " followers look on their own";
  }

  elements.back.addEventListener("click", () => {
    if (state !== "off") {
      handlers.send({ type: "free-look", state: "end" });
    }
  });
  elements.recall.addEventListener("click", () => {
    handlers.send({ type: "free-look-recall" });
  });

  update();
  return {
    active: () => state === "on",
    // A follower's gesture: ask for its own view, once.
    request() {
      if (state === "off") {
        state = "asked";
        handlers.send({ type: "free-look", state: "start" });
      }
    },
    // The page's role in a session changed (or it left one, or lost the connection).
    setRole(role) {
      presenting = role === "presenter";
      if (role !== "follower") {
        state = "off";
      }
      if (!presenting) {
        looking = 0;
      }
      update();
    },
    // A refusal of free look (the limit, no series yet): back to following.
    refused(error) {
      if (state === "asked" && error.message.startsWith("free-look")) {
        state = "off";
        update();
      }
    },
    // The server's free-look messages; false for any other message.
    onMessage(message) {
      if (message.type === "free-look-started") {
        const first = state !== "on";
        state = "on";
        update();
        if (first) {
          handlers.onStarted(message.camera || {});
        }
      } else if (message.type === "free-look-ended") {
        state = "off";
        update();
        handlers.onEnded(kEnded[message.reason] || "following the presenter");
      } else if (message.type === "free-look-state") {
        looking = message.looking;
        update();
      } else {
        return false;
      }
      return true;
    },
  };
};
