#!/usr/bin/env python3
"""Reads one session's exports back with the tools researchers open them with, and prints what
each tool read, with every problem found, as one JSON object (tests/corpus_export.rs compares it
with the session's log, tier by tier, time by time, text by text).

    check_exports.py EXPORT_DIR NAME

reads EXPORT_DIR/NAME.eaf, NAME.TextGrid and NAME.csv:

- EAF: pympi-ling reads the tiers, the act tiers' parent values and the vocabulary. pympi checks
  almost nothing, so the checks it lets pass are made here on the XML itself: the EAF 3.0
  schema's element order, one xsd:ID space without duplicates, no dangling reference (time
  slots, parents, linguistic types, constraints, vocabularies, languages, annotations), every
  CVE_REF in the vocabulary and equal to its value, no overlap on a tier, time slots in time
  order, lastUsedAnnotationId; each annotation tier's CVE_REFs name entries of its vocabulary
  equal to their values. (The EAF 3.0 XSD ships in no registry package, so no schema
  validator runs.)
- TextGrid: praatio (which refuses overlaps) and Praat's own parser (praat-parselmouth); the
  two must agree. Checked here: UTF-8 without a byte-order mark, every interval tier tiled from
  xmin to xmax, points sorted.
- CSV: Python's csv module (RFC 4180).
- Media: the EAF's MEDIA_DESCRIPTORs as pympi reads them (`get_linked_files`), each checked
  here: MEDIA_URL an absolute file:// URL of a file that is there, RELATIVE_MEDIA_URL `./` and
  the same file beside the EAF, EXTRACTED_FROM a file relative to the EAF's folder; each WAV
  read by Python's wave module and by Praat (parselmouth.Sound), which must agree.

Times are given as each format has them: EAF in ms, TextGrid and CSV in seconds.
"""

import csv
import json
import os
import re
import sys
import wave
from urllib.parse import unquote, urlparse
import xml.etree.ElementTree as ET

import parselmouth
import pympi
from parselmouth.praat import call
from praatio import textgrid

PROBLEMS = []


def problem(message):
    PROBLEMS.append(message)


# The EAF 3.0 schema's order of the document's children, and of the header's.
ROOT_ORDER = ["LICENSE", "HEADER", "TIME_ORDER", "TIER", "LINGUISTIC_TYPE", "LOCALE",
              "LANGUAGE", "CONSTRAINT", "CONTROLLED_VOCABULARY", "LEXICON_REF", "EXTERNAL_REF"]
HEADER_ORDER = ["MEDIA_DESCRIPTOR", "LINKED_FILE_DESCRIPTOR", "PROPERTY"]
# The attributes of type xsd:ID (one space); the other names are kept apart from them too.
ID_ATTRIBUTES = {"TIME_SLOT": "TIME_SLOT_ID", "ALIGNABLE_ANNOTATION": "ANNOTATION_ID",
                 "REF_ANNOTATION": "ANNOTATION_ID", "LANGUAGE": "LANG_ID",
                 "CV_ENTRY_ML": "CVE_ID", "TIER": "TIER_ID",
                 "LINGUISTIC_TYPE": "LINGUISTIC_TYPE_ID", "CONTROLLED_VOCABULARY": "CV_ID"}
NCNAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_.\-]*$")
STEREOTYPES = {"Time_Subdivision", "Symbolic_Subdivision", "Symbolic_Association", "Included_In"}
XSI = "{http://www.w3.org/2001/XMLSchema-instance}"


def in_order(children, order, where):
    ranks = []
    for child in children:
        if child.tag not in order:
            problem(f"{where}: unexpected element {child.tag}")
            return
        ranks.append(order.index(child.tag))
    if ranks != sorted(ranks):
        problem(f"{where}: elements out of the schema's order: {[c.tag for c in children]}")


def no_overlaps(name, spans):
    """spans: (start, end, value) of one tier; none may overlap or be empty."""
    for start, end, value in spans:
        if not start < end:
            problem(f"{name}: interval {start}..{end} {value!r} is not longer than zero")
    spans = sorted(spans)
    for a, b in zip(spans, spans[1:]):
        if a[1] > b[0]:
            problem(f"{name}: {a} overlaps {b}")


def check_eaf_xml(path):
    """The checks pympi does not make, on the XML itself; returns the CVE_REF of each act."""
    root = ET.parse(path).getroot()
    if root.tag != "ANNOTATION_DOCUMENT":
        problem(f"EAF root is {root.tag}")
    for name, value in [("FORMAT", "3.0"), ("VERSION", "3.0"), ("AUTHOR", None)]:
        if name not in root.attrib or (value and root.attrib[name] != value):
            problem(f"EAF: ANNOTATION_DOCUMENT {name}={root.attrib.get(name)!r}")
    if not re.match(r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d[+-]\d\d:\d\d$", root.attrib.get("DATE", "")):
        problem(f"EAF: DATE {root.attrib.get('DATE')!r} is not as ELAN writes it")
    if root.attrib.get(XSI + "noNamespaceSchemaLocation") != \
            "http://www.mpi.nl/tools/elan/EAFv3.0.xsd":
        problem("EAF: no xsi:noNamespaceSchemaLocation of EAF 3.0")
    in_order(list(root), ROOT_ORDER, "ANNOTATION_DOCUMENT")
    header = root.find("HEADER")
    in_order(list(header), HEADER_ORDER, "HEADER")
    if header.attrib.get("TIME_UNITS") != "milliseconds" or "MEDIA_FILE" not in header.attrib:
        problem(f"EAF: HEADER {header.attrib}")

    ids = {}
    for element in root.iter():
        attribute = ID_ATTRIBUTES.get(element.tag)
        if attribute is None:
            continue
        value = element.attrib.get(attribute)
        if value is None or not NCNAME.match(value):
            problem(f"EAF: {element.tag} {attribute}={value!r} is not an xsd:ID")
        elif value in ids:
            problem(f"EAF: {value!r} is the id of a {ids[value]} and of a {element.tag}")
        else:
            ids[value] = element.tag

    def named(tag, attribute):
        return {e.attrib[attribute]: e for e in root.iter(tag)}

    slots = named("TIME_SLOT", "TIME_SLOT_ID")
    values = [int(s.attrib["TIME_VALUE"]) for s in root.iter("TIME_SLOT")]
    if values != sorted(values):
        problem("EAF: time slots are not in time order")
    types = named("LINGUISTIC_TYPE", "LINGUISTIC_TYPE_ID")
    tiers = named("TIER", "TIER_ID")
    vocabularies = named("CONTROLLED_VOCABULARY", "CV_ID")
    languages = named("LANGUAGE", "LANG_ID")
    constraints = {c.attrib["STEREOTYPE"] for c in root.iter("CONSTRAINT")}
    if constraints != STEREOTYPES:
        problem(f"EAF: constraints {sorted(constraints)}, not ELAN's four")
    for element in root.iter():
        if "LANG_REF" in element.attrib and element.attrib["LANG_REF"] not in languages:
            problem(f"EAF: {element.tag} LANG_REF {element.attrib['LANG_REF']!r} dangles")
    for type_id, kind in types.items():
        if kind.attrib.get("CONSTRAINTS", "Symbolic_Association") not in constraints:
            problem(f"EAF: type {type_id} names a constraint that is not there")
        cv = kind.attrib.get("CONTROLLED_VOCABULARY_REF")
        if cv is not None and cv not in vocabularies:
            problem(f"EAF: type {type_id} names vocabulary {cv!r}, which is not there")

    annotation_tier = {}
    for tier_id, tier in tiers.items():
        for a in tier.iter("ALIGNABLE_ANNOTATION"):
            annotation_tier[a.attrib["ANNOTATION_ID"]] = tier_id
    cve_refs = {}
    for tier_id, tier in tiers.items():
        kind = types.get(tier.attrib["LINGUISTIC_TYPE_REF"])
        if kind is None:
            problem(f"EAF: tier {tier_id} has no linguistic type")
            continue
        parent = tier.attrib.get("PARENT_REF")
        if parent is not None and parent not in tiers:
            problem(f"EAF: tier {tier_id}'s parent {parent!r} is not there")
        spans = []
        for a in tier.iter("ALIGNABLE_ANNOTATION"):
            ends = [slots.get(a.attrib[r]) for r in ("TIME_SLOT_REF1", "TIME_SLOT_REF2")]
            if None in ends:
                problem(f"EAF: {a.attrib['ANNOTATION_ID']} names a missing time slot")
                continue
            start, end = (int(s.attrib["TIME_VALUE"]) for s in ends)
            spans.append((start, end, a.findtext("ANNOTATION_VALUE")))
        no_overlaps(f"EAF tier {tier_id}", spans)
        cv = vocabularies.get(kind.attrib.get("CONTROLLED_VOCABULARY_REF"))
        entries = {} if cv is None else {
            e.attrib["CVE_ID"]: e.findtext("CVE_VALUE") for e in cv.iter("CV_ENTRY_ML")}
        referred = set()
        for r in tier.iter("REF_ANNOTATION"):
            target = r.attrib["ANNOTATION_REF"]
            if annotation_tier.get(target) != parent:
                problem(f"EAF: {r.attrib['ANNOTATION_ID']} refers to {target!r}, "
                        f"not an annotation of its parent tier {parent}")
            if target in referred:
                problem(f"EAF: two annotations of {tier_id} refer to {target}")
            referred.add(target)
            value = r.findtext("ANNOTATION_VALUE")
            cve = r.attrib.get("CVE_REF")
            if cve not in entries:
                problem(f"EAF: {r.attrib['ANNOTATION_ID']} CVE_REF {cve!r} is not in the vocabulary")
            elif entries[cve] != value:
                problem(f"EAF: {r.attrib['ANNOTATION_ID']} says {value!r}, its CVE_REF {entries[cve]!r}")
            cve_refs.setdefault(tier_id, []).append(cve)
    numbers = [int(i[1:]) for i, tag in ids.items() if tag.endswith("_ANNOTATION")]
    last = dict((p.attrib["NAME"], p.text) for p in header.iter("PROPERTY"))
    if str(max(numbers, default=0)) != last.get("lastUsedAnnotationId"):
        problem(f"EAF: lastUsedAnnotationId {last.get('lastUsedAnnotationId')} "
                f"but the last annotation is a{max(numbers, default=0)}")
    return cve_refs


def read_coded(path):
    """The annotation tiers (a time-aligned tier whose linguistic type has a controlled
    vocabulary): for each, the vocabulary value each annotation's CVE_REF names, in time order;
    an annotation without a CVE_REF, or one naming an entry that is not there or says another
    value than the annotation, is a problem."""
    root = ET.parse(path).getroot()
    types = {t.attrib["LINGUISTIC_TYPE_ID"]: t for t in root.iter("LINGUISTIC_TYPE")}
    vocabularies = {v.attrib["CV_ID"]: v for v in root.iter("CONTROLLED_VOCABULARY")}
    slots = {s.attrib["TIME_SLOT_ID"]: int(s.attrib["TIME_VALUE"]) for s in root.iter("TIME_SLOT")}
    coded = {}
    for tier in root.iter("TIER"):
        kind = types.get(tier.attrib["LINGUISTIC_TYPE_REF"])
        if kind is None or kind.attrib.get("TIME_ALIGNABLE") != "true":
            continue
        cv = vocabularies.get(kind.attrib.get("CONTROLLED_VOCABULARY_REF"))
        if cv is None:
            continue
        entries = {e.attrib["CVE_ID"]: e.findtext("CVE_VALUE") for e in cv.iter("CV_ENTRY_ML")}
        values = []
        for a in tier.iter("ALIGNABLE_ANNOTATION"):
            value = a.findtext("ANNOTATION_VALUE")
            cve = a.attrib.get("CVE_REF")
            if cve not in entries:
                problem(f"EAF: {a.attrib['ANNOTATION_ID']} on {tier.attrib['TIER_ID']} has "
                        f"CVE_REF {cve!r}, not an entry of {cv.attrib['CV_ID']}")
                continue
            if entries[cve] != value:
                problem(f"EAF: {a.attrib['ANNOTATION_ID']} says {value!r}, its CVE_REF "
                        f"{entries[cve]!r}")
            start = slots[a.attrib["TIME_SLOT_REF1"]]
            end = slots[a.attrib["TIME_SLOT_REF2"]]
            values.append((start, end, entries[cve]))
        coded[tier.attrib["TIER_ID"]] = [v for (_, _, v) in sorted(values)]
    return coded


def read_eaf(path):
    eaf = pympi.Elan.Eaf(path)
    tiers, ref_tiers, parents = {}, {}, {}
    for name in eaf.get_tier_names():
        parent = eaf.get_parameters_for_tier(name).get("PARENT_REF")
        if parent is None:
            tiers[name] = sorted(eaf.get_annotation_data_for_tier(name))
        else:
            parents[name] = parent
            ref_tiers[name] = sorted(eaf.get_ref_annotation_data_for_tier(name))
    vocabulary = {}
    for cv in eaf.get_controlled_vocabulary_names():
        for cve_id, (values, _) in eaf.get_cv_entries(cv).items():
            vocabulary[cve_id] = values[0][0]
    return {"tiers": tiers, "ref_tiers": ref_tiers, "parents": parents,
            "vocabulary": vocabulary, "order": list(eaf.get_tier_names())}


def read_textgrid_praatio(path):
    grid = textgrid.openTextgrid(path, includeEmptyIntervals=False)
    tiers = {}
    for name in grid.tierNames:
        tier = grid.getTier(name)
        if isinstance(tier, textgrid.IntervalTier):
            tiers[name] = {"class": "IntervalTier",
                           "entries": [[e.start, e.end, e.label] for e in tier.entries]}
        else:
            tiers[name] = {"class": "TextTier",
                           "entries": [[e.time, e.label] for e in tier.entries]}
    return {"order": list(grid.tierNames), "tiers": tiers, "xmax": grid.maxTimestamp}


def read_textgrid_praat(path):
    """Praat's own reading, every interval (the empty ones too) and point."""
    grid = parselmouth.read(path)
    xmin, xmax = grid.xmin, grid.xmax
    tiers, order = {}, []
    for t in range(1, int(call(grid, "Get number of tiers")) + 1):
        name = call(grid, "Get tier name", t)
        order.append(name)
        if call(grid, "Is interval tier", t):
            intervals = []
            for i in range(1, int(call(grid, "Get number of intervals", t)) + 1):
                intervals.append([call(grid, "Get start time of interval", t, i),
                                  call(grid, "Get end time of interval", t, i),
                                  call(grid, "Get label of interval", t, i)])
            cursor = xmin
            for start, end, _ in intervals:
                if start != cursor:
                    problem(f"TextGrid tier {name}: not tiled at {cursor} (next starts {start})")
                cursor = end
            if cursor != xmax:
                problem(f"TextGrid tier {name}: ends at {cursor}, not at xmax {xmax}")
            no_overlaps(f"TextGrid tier {name}", [tuple(i) for i in intervals])
            labelled = [i for i in intervals if i[2] != ""]
            tiers[name] = {"class": "IntervalTier", "entries": labelled}
        else:
            points = []
            for i in range(1, int(call(grid, "Get number of points", t)) + 1):
                points.append([call(grid, "Get time of point", t, i),
                               call(grid, "Get label of point", t, i)])
            times = [p[0] for p in points]
            if times != sorted(set(times)):
                problem(f"TextGrid tier {name}: points not strictly in time order")
            tiers[name] = {"class": "TextTier", "entries": points}
    return {"order": order, "tiers": tiers, "xmin": xmin, "xmax": xmax}


def check_textgrid_bytes(path):
    raw = open(path, "rb").read()
    if raw.startswith(b"\xef\xbb\xbf"):
        problem("TextGrid starts with a byte-order mark")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        problem(f"TextGrid is not UTF-8: {e}")
        return
    if not text.startswith('File type = "ooTextFile"\nObject class = "TextGrid"\n'):
        problem("TextGrid does not start as Praat's long text format does")


def agree(praatio_read, praat_read):
    """praatio and Praat must read the same tiers, times and labels (praatio keeps doubled
    quotes in point marks and strips spaces from labels: compared with that in mind)."""
    if praatio_read["order"] != praat_read["order"]:
        problem(f"praatio reads tiers {praatio_read['order']}, Praat {praat_read['order']}")
        return
    for name, tier in praat_read["tiers"].items():
        theirs = praatio_read["tiers"][name]
        mine = tier["entries"]
        if tier["class"] != theirs["class"] or len(mine) != len(theirs["entries"]):
            problem(f"TextGrid tier {name}: praatio and Praat read different entries")
            continue
        for a, b in zip(mine, theirs["entries"]):
            label_a = a[-1].strip()
            label_b = b[-1].replace('""', '"') if tier["class"] == "TextTier" else b[-1]
            if [round(x, 6) for x in a[:-1]] != [round(x, 6) for x in b[:-1]] \
                    or label_a != label_b.strip():
                problem(f"TextGrid tier {name}: Praat reads {a}, praatio {b}")


def read_csv(path):
    raw = open(path, "rb").read()
    if raw.startswith(b"\xef\xbb\xbf"):
        problem("CSV starts with a byte-order mark")
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    for n, row in enumerate(rows[1:], 2):
        if len(row) != len(rows[0]):
            problem(f"CSV line {n} has {len(row)} fields, the header {len(rows[0])}")
    for n, row in enumerate(rows, 1):
        for cell in row:
            if cell[:1] in ("=", "+", "-", "@", "\t", "\r"):
                problem(f"CSV line {n}: a spreadsheet would run the cell {cell!r} as a formula")
    starts = [float(r[0]) for r in rows[1:]]
    if starts != sorted(starts):
        problem("CSV rows are not sorted by start")
    return {"header": rows[0], "rows": rows[1:]}


def read_media(path):
    """The EAF's linked media as pympi reads them, each WAV as `wave` and Praat read it."""
    folder = os.path.dirname(os.path.abspath(path))
    media = []
    for linked in pympi.Elan.Eaf(path).get_linked_files():
        url = urlparse(linked["MEDIA_URL"])
        absolute = unquote(url.path)
        relative = linked.get("RELATIVE_MEDIA_URL", "")
        extracted = linked.get("EXTRACTED_FROM", "")
        if url.scheme != "file" or not os.path.isabs(absolute) or not os.path.isfile(absolute):
            problem(f"EAF: MEDIA_URL {linked['MEDIA_URL']!r} is not a file that is there")
            continue
        beside = os.path.join(folder, relative)
        if not relative.startswith("./") or not os.path.samefile(beside, absolute):
            problem(f"EAF: RELATIVE_MEDIA_URL {relative!r} is not {absolute} beside the EAF")
        if not os.path.isfile(os.path.join(folder, extracted)):
            problem(f"EAF: EXTRACTED_FROM {extracted!r} is not a file from the EAF's folder")
        entry = {"relative": relative, "mime": linked["MIME_TYPE"], "extracted_from": extracted,
                 "time_origin": linked.get("TIME_ORIGIN")}
        if linked["MIME_TYPE"] == "audio/x-wav":
            with wave.open(absolute) as w:
                entry.update(rate=w.getframerate(), channels=w.getnchannels(),
                             width=w.getsampwidth(), frames=w.getnframes())
            sound = parselmouth.Sound(absolute)
            if (round(sound.sampling_frequency), sound.n_channels, sound.n_samples) != \
                    (entry["rate"], entry["channels"], entry["frames"]):
                problem(f"Praat reads {relative} as {sound.sampling_frequency} Hz, "
                        f"{sound.n_channels} channels, {sound.n_samples} samples; wave otherwise")
        media.append(entry)
    return media


def attempt(what, read, path):
    """A reader's result; a reader that refuses the file is a problem, not a crash."""
    try:
        return read(path)
    except Exception as e:  # noqa: BLE001 - whatever a reader raises is the finding
        problem(f"{what} cannot read {path}: {type(e).__name__}: {e}")
        return None


def main():
    folder, name = sys.argv[1], sys.argv[2]
    base = f"{folder}/{name}"
    summary = {"eaf": attempt("pympi", read_eaf, base + ".eaf"),
               "eaf_cve_refs": attempt("the EAF checks", check_eaf_xml, base + ".eaf"),
               "eaf_coded": attempt("the EAF annotation checks", read_coded, base + ".eaf"),
               "eaf_media": attempt("the EAF media checks", read_media, base + ".eaf")}
    check_textgrid_bytes(base + ".TextGrid")
    summary["textgrid_praatio"] = attempt("praatio", read_textgrid_praatio, base + ".TextGrid")
    summary["textgrid_praat"] = attempt("Praat", read_textgrid_praat, base + ".TextGrid")
    if summary["textgrid_praatio"] and summary["textgrid_praat"]:
        agree(summary["textgrid_praatio"], summary["textgrid_praat"])
    summary["csv"] = attempt("csv", read_csv, base + ".csv")
    summary["problems"] = PROBLEMS
    json.dump(summary, sys.stdout, ensure_ascii=False)


if __name__ == "__main__":
    main()
