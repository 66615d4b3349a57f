// access.js: signing in and staying signed in. Opens the connection (connection.js) with the
// credential from the sign-in form, or the one this tab kept, or none on an `--open` server;
// keeps it for this tab once the server accepts it, and forgets it when it is refused: then the
// form asks again. A lockout (too many wrong or missing credentials from this computer; the
// server always takes the right one, so only a credential it never accepted meets one) is
// waited out with a countdown banner and the credential kept, with no form over the console,
// and tried once more after the wait. The link indicator says which of these
// states the console is in.

import { connect } from "./connection.js";
import * as signin from "./signin.js";

/**
 * The elements `createAccess` works with, by the ids the console and the preview share
 * (`link`, `lockout`, `signout`, and the `signin` dialog's).
 * @param {(id: string) => HTMLElement} byId
 */
export function accessElements(byId) {
  return {
    link: byId("link"),
    banner: byId("lockout"),
    signout: byId("signout"),
    form: {
      dialog: byId("signin"),
      form: byId("signin-form"),
      token: byId("signin-token"),
      name: byId("signin-name"),
      error: byId("signin-error"),
    },
  };
}

/**
 * @param {{path: string, open: boolean, link: HTMLElement, banner: HTMLElement,
 *          signout: HTMLElement, form: {dialog: HTMLDialogElement, form: HTMLFormElement,
 *          token: HTMLInputElement, name: HTMLInputElement, error: HTMLElement},
 *          onFrame: (frame: object) => void, onOnline: () => void, onClosed: (reason: string) => void,
 *          onSignedOut: () => void}} options `path`: the websocket's; `open`: an `--open`
 *          server, which needs no credential; `banner`: the lockout banner; `form`: the
 *          sign-in dialog's elements; `onOnline`: welcomed; `onClosed(reason)`: Docent closed
 *          the connection and said why; `onSignedOut`: the credential is given up (signed out or
 *          refused).
 * @returns {{begin: () => void, connection: () => object|null, token: () => string|null,
 *          name: () => string|null, signedIn: () => boolean,
 *          showLockout: (retryAt: number|null) => void}} `begin`: signs in as the page
 *          starts; `connection`: the websocket's (connection.js), null when signed out.
 */
export function createAccess({ path, open, link, banner, signout, form, onFrame, onOnline, onClosed, onSignedOut }) {
  let connection = null;
  let signedIn = false;
  let token = null;
  let verified = false; // the server accepted `token` before (or it was kept from this tab's sign-in)
  let lockouts = 0; // `too-many-attempts` answers in a row
  let name = null;
  let lockoutTimer = null;

  const dialog = signin.createSignIn({ ...form, onSubmit: (credentials) => start(credentials.token, credentials.name) });

  function onStatus(status) {
    link.dataset.state = status.state;
    if (status.state !== "locked") showLockout(null);
    if (status.state === "online") {
      link.textContent = "connected";
      signedIn = true;
      verified = true;
      lockouts = 0;
      if (token) signin.remember(token, name);
      onOnline();
    } else if (status.state === "connecting") {
      link.textContent = "connecting…";
    } else if (status.state === "offline") {
      link.textContent = "offline: reconnecting…";
      if (status.message) onClosed(status.message);
    } else if (status.state === "locked") {
      // Too many wrong or missing credentials from this computer: the server refuses wrong ones
      // for a while (never the right one). The credential is kept and tried again after the
      // wait, with no sign-in form over the console. One refused again right after the wait is
      // given up: the server answers a wrong one with `too-many-attempts` then as well, and
      // retrying it would keep this computer waiting for good.
      lockouts += 1;
      if (!verified && lockouts >= 2) {
        connection?.close();
        refused("Still refused after the wait: the credential is probably wrong. Check it and try again.");
        return;
      }
      link.textContent = "locked out: waiting";
      showLockout(status.retryAt);
    } else if (status.state === "refused") {
      // A wrong credential: forget it and ask again.
      refused("That credential was refused. Check it and try again.");
    }
  }

  /** The credential is given up: forget it and ask for one, saying `why`. */
  function refused(why) {
    link.textContent = "signed out";
    link.dataset.state = "refused";
    showLockout(null);
    signedIn = false;
    connection = null;
    onSignedOut();
    signin.forget();
    token = null;
    verified = false;
    dialog.ask(why);
  }

  /** The lockout banner counting down to `retryAt` (ms, this computer's clock); null hides it. */
  function showLockout(retryAt) {
    clearInterval(lockoutTimer);
    lockoutTimer = null;
    if (retryAt === null || retryAt === undefined) {
      banner.hidden = true;
      return;
    }
    const show = () => {
      const left = Math.max(0, Math.ceil((retryAt - Date.now()) / 1000));
      banner.dataset.seconds = String(left);
      banner.textContent =
        left > 0
          ? `Too many wrong or missing credentials from this computer: Docent refuses wrong ones from it for ${left} s more (the right credential is always taken). The console tries this one once more then. Stop tries the server all the same.`
          : "Signing in again…";
    };
    show();
    banner.hidden = false;
    lockoutTimer = setInterval(show, 1000);
  }

  /** Signs in with `credential` (null on an open development server). */
  function start(credential, operatorName, { kept = false } = {}) {
    connection?.close();
    token = credential;
    verified = kept; // a kept credential was accepted in this tab before
    lockouts = 0;
    name = operatorName || name || "operator";
    connection = connect({ path, token, name, onFrame, onStatus });
  }

  function signOut() {
    connection?.close();
    connection = null;
    signedIn = false;
    showLockout(null);
    onSignedOut();
    signin.forget();
    token = null;
    link.textContent = "signed out";
    link.dataset.state = "offline";
    dialog.ask();
  }

  signout.addEventListener("click", signOut);

  return {
    begin() {
      if (open) {
        signout.hidden = true;
        start(null, signin.stored().name);
      } else {
        const saved = signin.stored();
        if (saved.token) start(saved.token, saved.name, { kept: true });
        else dialog.ask();
      }
    },
    connection: () => connection,
    token: () => token,
    name: () => name,
    signedIn: () => signedIn,
    showLockout,
  };
}
