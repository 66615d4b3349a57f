// signin.js: asking for the operator credential. It is kept in sessionStorage for this tab
// only (gone when the tab closes, never put in a URL) and the operator's name in
// localStorage. The dialog cannot be dismissed: without a credential there is no console.

const TOKEN = "docent.operator.token";
const NAME = "docent.operator.name";

/** The stored credential and name: `{token, name}` (either may be null). */
export function stored() {
  let token = null;
  let name = null;
  try {
    token = sessionStorage.getItem(TOKEN);
    name = localStorage.getItem(NAME);
  } catch {
    // Storage disabled: ask every time.
  }
  return { token: token || null, name: name || null };
}

/** Keeps the credential for this tab and the name for this browser. */
export function remember(token, name) {
  try {
    if (token) sessionStorage.setItem(TOKEN, token);
    if (name) localStorage.setItem(NAME, name);
  } catch {
    // Storage disabled: the console works until the page is reloaded.
  }
}

/** Forgets the credential (sign-out, refused). */
export function forget() {
  try {
    sessionStorage.removeItem(TOKEN);
  } catch {
    // Nothing stored.
  }
}

/**
 * The sign-in dialog.
 * @param {{dialog: HTMLDialogElement, form: HTMLFormElement, token: HTMLInputElement,
 *          name: HTMLInputElement, error: HTMLElement,
 *          onSubmit: (credentials: {token: string, name: string}) => void}} els
 */
export function createSignIn({ dialog, form, token, name, error, onSubmit }) {
  dialog.addEventListener("cancel", (event) => event.preventDefault());
  form.addEventListener("submit", (event) => {
    event.preventDefault();
    const credentials = { token: token.value.trim(), name: name.value.trim() };
    if (!credentials.token) return;
    token.value = "";
    dialog.close();
    onSubmit(credentials);
  });
  return {
    /** Shows the dialog, with `message` (a refusal) when given. */
    ask(message = null) {
      error.textContent = message ?? "";
      error.hidden = !message;
      name.value = stored().name ?? name.value;
      if (!dialog.open) dialog.showModal();
      token.focus();
    },
  };
}
