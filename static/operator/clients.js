// clients.js: who is connected: kiosks, projectors, adapters (with their verbs), dialog
// managers and other operators, from GET /api/state `clients` and the client.connected and
// client.left events. This console's own connection is marked "you".

import { h } from "./dom.js";

const ROLE_ORDER = ["kiosk", "projector", "adapter", "dm", "operator"];
const ROLE_NAMES = { kiosk: "kiosk", projector: "projector", adapter: "adapter", dm: "dialog manager", operator: "operator" };

/**
 * @param {HTMLElement} list the <ul> to fill
 * @param {(clients: Map<number, object>) => void} onChange called with every change
 */
export function createClients(list, onChange = () => {}) {
  const clients = new Map(); // id -> {role, name, verbs}
  const left = new Set(); // ids seen leaving: a late snapshot must not bring them back
  let me = null;

  function render() {
    const sorted = [...clients].sort(
      ([a, x], [b, y]) => ROLE_ORDER.indexOf(x.role) - ROLE_ORDER.indexOf(y.role) || a - b,
    );
    const roles = new Set(sorted.map(([, c]) => c.role));
    const missing = ["kiosk", "projector"].filter((r) => !roles.has(r));
    list.replaceChildren(
      ...sorted.map(([id, c]) =>
        h(
          "li",
          { class: `client role-${c.role}`, dataset: { client: String(id), role: c.role } },
          h("span", { class: "client-role" }, ROLE_NAMES[c.role] ?? c.role),
          ` ${c.name ?? ""}`,
          h("span", { class: "muted small" }, ` #${id}`),
          id === me ? h("strong", { class: "small" }, " (you)") : null,
          c.verbs?.length ? h("span", { class: "muted small" }, ` ${c.verbs.join(" ")}`) : null,
        ),
      ),
      ...missing.map((r) => h("li", { class: "client absent" }, `no ${ROLE_NAMES[r]} connected`)),
    );
    onChange(clients);
  }

  return {
    /** A new connection: `me` is its client id; forget the old one's list. */
    welcome(id) {
      me = id;
      clients.clear();
      left.clear();
      render();
    },
    /** GET /api/state `clients`. */
    snapshot(map) {
      for (const [id, c] of Object.entries(map ?? {})) {
        if (!left.has(Number(id))) clients.set(Number(id), { role: c.role, name: c.name ?? null, verbs: c.verbs ?? [] });
      }
      render();
    },
    event(e) {
      if (e.type === "client.connected") {
        left.delete(e.client);
        clients.set(e.client, { role: e.role, name: e.name ?? null, verbs: e.verbs ?? [] });
        render();
      } else if (e.type === "client.left") {
        left.add(e.client);
        clients.delete(e.client);
        render();
      }
    },
    get: () => clients,
  };
}
