// corpusbanner.js: the corpus banner. While the corpus log cannot be written (a full or
// read-only disk) the server refuses triggers; this banner says so in the server's own words
// (what happened, what to do), from `welcome`/`state` (state.corpus) and `corpus.unwritable`
// events, until `corpus.writable`, whose words (with any events lost meanwhile) it shows for
// a moment; so for a log file removed under the server and made again (`corpus.recreated`).
// Nothing is decided here: the server sends the words.

const SHOWN_MS = 15_000;

/**
 * @param {HTMLElement} element the banner (hidden when there is nothing to say)
 * @returns {{onFrame: (frame: object) => void}}
 */
export function createCorpusBanner(element) {
  let failing = null; // the words while the log cannot be written
  let passing = []; // words shown for a moment (recovered, made again, lost)
  let timer = null;

  function render() {
    const lines = failing ? [failing, ...passing] : passing;
    element.replaceChildren(
      ...lines.map((text) => {
        const p = document.createElement("p");
        p.textContent = text;
        return p;
      }),
    );
    element.hidden = lines.length === 0;
    element.dataset.state = failing ? "failing" : "told";
  }

  function tell(text) {
    passing = [...passing, text];
    clearTimeout(timer);
    timer = setTimeout(() => {
      passing = [];
      render();
    }, SHOWN_MS);
  }

  function onFrame(frame) {
    if (frame.type === "welcome" || frame.type === "state") {
      failing = frame.state?.corpus ?? null;
      render();
      return;
    }
    if (frame.type !== "event") return;
    const e = frame.event ?? {};
    if (e.type === "corpus.unwritable") failing = e.message;
    else if (e.type === "corpus.writable") {
      failing = null;
      tell(e.message);
    } else if (e.type === "corpus.recreated") tell(e.message);
    else if (e.type === "corpus.gap") tell(`${e.count} events (seq ${e.from} to ${e.to}) are not in the corpus: ${e.reason}.`);
    else return;
    render();
  }

  render();
  return { onFrame };
}
