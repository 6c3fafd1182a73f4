// Lucent browser client: teaching sessions and their invites. Joining one as a
// follower by its id (a join link's page is joined by the server itself),
// starting one as its presenter, leaving it; the presenter's invite: its link
// with a copy button, its QR code drawn from the server's module matrix, when it
// expires, and revoking it. app.js passes it the server's session messages and
// asks it what the page is in a session. Plain JavaScript, no build step.
"use strict";

window.createLucentSessions = (invite, handlers) => {
  const $ = (id) => document.getElementById(id);
  const ui = {
    sessionId: $("session-id"), joinSession: $("join-session"),
    startSession: $("start-session"), leaveSession: $("leave-session"),
    sessionInfo: $("session-info"), createInvite: $("create-invite"),
    inviteBox: $("invite-box"), inviteLink: $("invite-link"), copyInvite: $("copy-invite"),
    inviteQr: $("invite-qr"), inviteExpiry: $("invite-expiry"),
    revokeInvite: $("revoke-invite"),
  };
  const kQrQuietZone = 4; // light modules around a QR code
  const kByInvite = "by invite"; // `joining` of a join link's page: the server joins it
  const send = handlers.send;

  let session = null;      // {id, role: "presenter" | "follower"} while in a session
  // The session id asked for (or kByInvite), until session-state says the role: the
  // server sends `opened`, the last frame and the marks before it, to a follower.
  let joining = null;
  let shownInvite = null;  // the presenter's last invite-created

  function joinSession(id) {
    joining = id;
    handlers.onJoining();
    send({ type: "session-join", session: id });
    ui.sessionInfo.textContent = "joining session " + id + " ...";
  }

  function onSessionMessage(message) {
    if (message.type === "session-created") {
      session = { id: message.session, role: "presenter" };
      ui.sessionId.value = message.session;
    } else if (message.type === "session-state") {
      joining = null;
      session = { id: message.session, role: message.role };
      handlers.onRole(message.role);
      const others = Math.max(0, message.members - 1);
      ui.sessionInfo.textContent = message.role === "presenter"
        ? "presenting session " + message.session + " to " + others + " follower(s)"
        : "following session " + message.session + " (" + message.members + " members)";
    } else if (message.type === "session-left") {
      session = null;
      handlers.onLeft();
      showInvite(null);
      if (invite) {
        handlers.stopReconnecting(); // the server closes: an invite follows one session only
        handlers.setStatus("the session has ended");
        return;
      }
      ui.sessionInfo.textContent = "left the session; open a series";
      send({ type: "list" });
    } else if (message.type === "invite-created") {
      showInvite(message);
    } else if (message.type === "invite-revoked") {
      if (shownInvite && shownInvite.invite === message.invite) {
        showInvite(null);
      }
      handlers.setStatus(
        "invite revoked: its link lets no one in, and its followers were dropped");
    }
  }

  // --- invites (the presenter's) ---------------------------------------------

  function showInvite(created) {
    shownInvite = created;
    ui.inviteBox.hidden = created === null;
    if (created === null) {
      ui.inviteLink.value = "";
      return;
    }
    ui.inviteLink.value = created.link;
    ui.inviteExpiry.textContent = "valid until " + new Date(created.expires * 1000)
      .toLocaleString() + " or the end of the session";
    drawQr(ui.inviteQr, created.qr);
  }

  // The server's module matrix, dark on white, with its quiet zone.
  function drawQr(canvas, qr) {
    const modules = qr.size + 2 * kQrQuietZone;
    const scale = Math.max(2, Math.floor(256 / modules));
    canvas.width = canvas.height = modules * scale;
    const g = canvas.getContext("2d");
    g.fillStyle = "#fff";
    g.fillRect(0, 0, canvas.width, canvas.height);
    g.fillStyle = "#000";
    qr.rows.forEach((row, y) => {
      for (let x = 0; x < row.length; ++x) {
        if (row[x] === "1") {
          g.fillRect((x + kQrQuietZone) * scale, (y + kQrQuietZone) * scale, scale, scale);
        }
      }
    });
  }

  ui.createInvite.addEventListener("click", () => {
    // The link starts with what this page was loaded from (the host students reach).
    send({ type: "invite-create", origin: location.origin });
  });
  ui.revokeInvite.addEventListener("click", () => {
    if (shownInvite) {
      send({ type: "invite-revoke", invite: shownInvite.invite });
    }
  });
  ui.copyInvite.addEventListener("click", () => {
    ui.inviteLink.select();
    const copied = navigator.clipboard ? navigator.clipboard.writeText(ui.inviteLink.value)
      : Promise.resolve(document.execCommand("copy"));
    copied.then(() => handlers.setStatus("link copied", "good"),
                () => handlers.setStatus("select the link and copy it", "bad"));
  });

  ui.joinSession.addEventListener("click", () => {
    const id = ui.sessionId.value.trim();
    if (!id) {
      handlers.setStatus("enter the session id the presenter gave", "bad");
      return;
    }
    joinSession(id);
    handlers.updateControls();
  });
  ui.startSession.addEventListener("click", () => {
    send({ type: "session-create" });
  });
  ui.leaveSession.addEventListener("click", () => send({ type: "session-leave" }));

  return {
    session: () => session,
    joining: () => joining !== null,
    shownInvite: () => shownInvite,
    onMessage: onSessionMessage,
    // hello on a join link's page: the server joins the invite's session by itself.
    joinByInvite() {
      joining = kByInvite;
    },
    // hello after a reconnect: a follower comes back to its session.
    rejoin() {
      if (session) {
        joinSession(session.id);
      }
    },
    // An error: a join that found no session, or no room in it, is over.
    refused(error) {
      if (joining && (error.code === "not-found" || error.code === "session-full")) {
        joining = null;
        session = null;
        ui.sessionInfo.textContent = "";
      }
    },
    // The connection is gone: a join is asked again after hello; the server
    // hands a presented session on, and the page comes back on its own view.
    disconnected() {
      joining = null;
      if (session && session.role === "presenter") {
        session = null;
      }
    },
    updateControls(authenticated, protocolVersion) {
      ui.joinSession.disabled = !authenticated || session !== null || joining !== null;
      ui.startSession.disabled = ui.joinSession.disabled;
      ui.leaveSession.disabled = !authenticated || session === null;
      ui.createInvite.disabled = !authenticated || protocolVersion < 3 || session === null ||
                                 session.role !== "presenter";
      ui.revokeInvite.disabled = ui.createInvite.disabled || shownInvite === null;
    },
  };
};
