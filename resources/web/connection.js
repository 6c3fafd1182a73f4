// Lucent browser client: the connection. A WebSocket to the server that served
// this page, offering the protocol versions the page speaks; the token, or a
// join link's invite, rides in a subprotocol when it can, else the token goes
// in the first message, never in the URL. A lost connection is tried again
// with backoff (0.5 s doubling to 15 s) until the page stops it (a refused
// token or invite, the end of an invite's session). app.js handles what
// arrives. Plain JavaScript, no build step.
"use strict";

window.createLucentConnection = (invite, handlers) => {
  // The protocol versions this page speaks, newest first, offered in the
  // handshake: the server selects the first it speaks and says it in hello.
  const kSubprotocols = ["lucent.v4", "lucent.v3", "lucent.v2", "lucent.v1"];
  const kTokenSubprotocolPrefix = "lucent.token.";
  const kInviteSubprotocolPrefix = "lucent.invite.";
  // Characters a WebSocket subprotocol may hold (RFC 6455, an HTTP token).
  const kSubprotocolChars = /^[!#$%&'*+\-.^_`|~0-9A-Za-z]+$/;
  const kBackoffFirstMs = 500;
  const kBackoffMaxMs = 15000;

  let token = "";
  let socket = null;
  let reconnectTimer = 0;
  let backoffMs = kBackoffFirstMs;
  let stopReconnecting = false;

  function send(message) {
    if (socket && socket.readyState === WebSocket.OPEN) {
      socket.send(JSON.stringify(message));
    }
  }

  function connect() {
    clearTimeout(reconnectTimer);
    if (socket) {
      socket.onclose = null;
      socket.close();
    }
    stopReconnecting = false;
    handlers.onConnecting();
    handlers.setStatus("connecting to " + location.host + " ...");
    const scheme = location.protocol === "https:" ? "wss:" : "ws:";
    // The token rides in a subprotocol when it can (no extra round trip), else in
    // the first message; never in the URL. An invite's code always can.
    const tokenInProtocol = invite !== "" || kSubprotocolChars.test(token);
    const protocols = [...kSubprotocols];
    if (invite) {
      protocols.push(kInviteSubprotocolPrefix + invite);
    } else if (tokenInProtocol) {
      protocols.push(kTokenSubprotocolPrefix + token);
    }
    socket = new WebSocket(scheme + "//" + location.host + "/", protocols);
    socket.binaryType = "arraybuffer";
    socket.onopen = () => {
      handlers.setStatus("authenticating ...");
      if (!tokenInProtocol) {
        send({ type: "auth", token });
      }
    };
    socket.onmessage = (event) => {
      if (typeof event.data === "string") {
        handlers.onText(event.data);
      } else {
        handlers.onBinary(event.data);
      }
    };
    socket.onclose = (event) => onClosed(event);
  }

  function onClosed(event) {
    handlers.onClosed();
    if (stopReconnecting) {
      return;
    }
    const why = event.reason ? " (" + event.reason + ")" : "";
    handlers.setStatus("disconnected" + why + "; reconnecting in " +
                       (backoffMs / 1000).toFixed(1) + " s", "bad");
    reconnectTimer = setTimeout(connect, backoffMs * (0.8 + 0.4 * Math.random()));
    backoffMs = Math.min(backoffMs * 2, kBackoffMaxMs);
  }

  window.addEventListener("online", () => {
    if (token && !stopReconnecting && (!socket || socket.readyState === WebSocket.CLOSED)) {
      backoffMs = kBackoffFirstMs;
      connect();
    }
  });

  return {
    send,
    // Connects (again) with this token, from the first step of the backoff.
    start(newToken) {
      token = newToken;
      backoffMs = kBackoffFirstMs;
      connect();
    },
    // hello: the next loss of the connection starts the backoff anew.
    authenticated() {
      backoffMs = kBackoffFirstMs;
    },
    // No more tries: a new token (or invite) is needed, or the session has ended.
    stopReconnecting() {
      stopReconnecting = true;
    },
    stopped: () => stopReconnecting,
  };
};
