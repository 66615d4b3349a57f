// preview.js: fits the preview's two screens (the kiosk shell and the projector, each shown at
// its real pixel size in a frame) into the window side by side, scaling them down as needed.

function fit() {
  const screens = [...document.querySelectorAll(".screen")];
  const width = (window.innerWidth - 48) / screens.length;
  for (const screen of screens) {
    const w = Number(screen.dataset.width);
    const h = Number(screen.dataset.height);
    const scale = Math.min(1, width / w, (window.innerHeight - 80) / h);
    const frame = screen.querySelector("iframe");
    frame.style.transform = `scale(${scale})`;
    const viewport = screen.querySelector(".viewport");
    viewport.style.width = `${w * scale}px`;
    viewport.style.height = `${h * scale}px`;
  }
}

window.addEventListener("resize", fit);
fit();
