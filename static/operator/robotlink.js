// robotlink.js: the link to the robot's ROS side (rosbridge, docs/ROBOT.md) beside the
// console's own: up, or down and being retried, with the address and the reason on hover.
// Hidden on sites without one. Fed by `robot.link` events and the /api/state snapshot.

/**
 * @param {HTMLElement} element
 * @returns {{set(link: {state: string, url: string, reason?: string|null}|null): void}}
 */
export function createRobotLink(element) {
  return {
    set(link) {
      element.hidden = !link;
      if (!link) return;
      const up = link.state === "up";
      element.dataset.state = up ? "online" : "offline";
      element.textContent = up ? "robot linked" : "robot link down, retrying";
      element.title = up ? link.url : `${link.url}: ${link.reason ?? "not connected"}`;
    },
  };
}
