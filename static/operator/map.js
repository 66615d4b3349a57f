// map.js: the robot on the bundle's map image (GET /api/operator `map`). The image spans the
// drive's bounds: x grows to the right, y upwards, heading in degrees counter-clockwise from
// the x axis. The robot is an arrow moved on each `pose` event; the target of the last
// SET_WAYPOINT is a ring.

import { h } from "./dom.js";

/**
 * @param {{panel: HTMLElement, view: HTMLElement, text: HTMLElement}} els
 * @returns {{configure(map: object|null): void, pose(p: object|null): void,
 *            waypoint(w: object|null): void}}
 */
export function createMap({ panel, view, text }) {
  let bounds = null;
  const robot = h("div", { class: "robot", "aria-hidden": "true" });
  const target = h("div", { class: "waypoint", "aria-hidden": "true", hidden: true });

  const place = (el, x, y) => {
    el.style.left = `${((x - bounds.min_x) / (bounds.max_x - bounds.min_x)) * 100}%`;
    el.style.top = `${((bounds.max_y - y) / (bounds.max_y - bounds.min_y)) * 100}%`;
  };

  return {
    configure(map) {
      bounds = map?.bounds ?? null;
      panel.hidden = !map;
      if (!map) return;
      const image = h("img", { src: map.url, alt: "map of the site" });
      view.replaceChildren(image, target, robot);
      robot.hidden = true;
    },
    pose(p) {
      if (!p) return;
      text.textContent = `x ${p.x.toFixed(1)} y ${p.y.toFixed(1)} · ${Math.round(p.heading)}°${p.moving ? " · driving" : ""}`;
      if (!bounds) return;
      place(robot, p.x, p.y);
      robot.style.transform = `translate(-50%, -50%) rotate(${-p.heading}deg)`;
      robot.classList.toggle("moving", Boolean(p.moving));
      robot.hidden = false;
    },
    waypoint(w) {
      if (!bounds || !w) return;
      place(target, w.x, w.y);
      target.hidden = false;
    },
  };
}

