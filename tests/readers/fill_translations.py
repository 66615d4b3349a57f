"""Fills a table made by `docent translations export` as a translator's tools do: a CSV with
Python's csv module (as a spreadsheet saves it), an XLIFF 1.2 file with translate-toolkit's
API (as a CAT tool does). tests/translations.rs runs it and imports what it writes.

Usage: fill_translations.py IN OUT FILLS_JSON

FILLS_JSON maps keys (GREETING/Text/1) to their translations; every other text stays as it
is. Prints what the reader found, as JSON: the languages and, in the file's order, each
text's key, source, target and note.
"""

import csv
import json
import sys


def fill_csv(src, dst, fills):
    with open(src, newline="", encoding="utf-8-sig") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    key, where = header.index("key"), header.index("where")
    source, target = 1, 2
    found = {"source_language": header[source], "target_language": header[target], "texts": []}
    for row in rows[1:]:
        found["texts"].append(
            {"key": row[key], "source": row[source], "target": row[target], "note": row[where]}
        )
        if row[key] in fills:
            row[target] = fills[row[key]]
    with open(dst, "w", newline="", encoding="utf-8-sig") as f:
        csv.writer(f).writerows(rows)
    return found


def fill_xliff(src, dst, fills):
    from translate.storage import xliff

    with open(src, "rb") as f:
        store = xliff.xlifffile.parsestring(f.read())
    found = {
        "source_language": store.getsourcelanguage(),
        "target_language": store.gettargetlanguage(),
        "texts": [],
    }
    for unit in store.units:
        # translate-toolkit names a unit by its file's `original`, \x04 and the unit's id.
        key = unit.getid().rsplit("\x04", 1)[-1]
        found["texts"].append(
            {
                "key": key,
                "source": unit.source,
                "target": unit.target,
                "note": unit.getnotes(),
                "state": unit.get_state_id(),
            }
        )
        if key in fills:
            unit.target = fills[key]
    store.savefile(dst)
    return found


def main():
    src, dst, fills = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
    fill = fill_csv if src.endswith(".csv") else fill_xliff
    print(json.dumps(fill(src, dst, fills), ensure_ascii=False))


main()
