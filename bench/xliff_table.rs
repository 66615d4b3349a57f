//! A generated XLIFF 1.2 table of translations, shaped as `docent translations export` writes
//! one (a unit per text, each on its lines, with a note), of at least a given size: for
//! `bench/xliff.rs` and the reader's linearity test (`server/content/translations/xliff_tests.rs`).

/// A table of at least `min_bytes`, in German, and how many units it has.
pub fn table(min_bytes: usize) -> (String, usize) {
    let mut out = String::with_capacity(min_bytes + 1024);
    out.push_str(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<xliff version=\"1.2\" \
         xmlns=\"urn:oasis:names:tc:xliff:document:1.2\">\n  <file original=\"tour\" \
         source-language=\"en\" target-language=\"de\" datatype=\"plaintext\">\n    <body>\n",
    );
    let mut units = 0;
    while out.len() < min_bytes {
        units += 1;
        out.push_str(&format!(
            "      <trans-unit id=\"ROOM_{units}/Text/1\" xml:space=\"preserve\">\n        \
             <source>Welcome to room {units}: paintings &amp; sculptures from 1850 to \
             1900.</source>\n        <target state=\"translated\">Willkommen in Raum \
             {units}: Gemälde &amp; Skulpturen von 1850 bis 1900.</target>\n        \
             <note from=\"docent\">acts.yaml:{units}</note>\n      </trans-unit>\n"
        ));
    }
    out.push_str("    </body>\n  </file>\n</xliff>\n");
    (out, units)
}

/// A table whose one target nests `depth` inline elements, each on a line with a word.
pub fn nested(depth: usize) -> String {
    let mut out = String::from(
        "<?xml version=\"1.0\"?>\n<xliff version=\"1.2\"><file source-language=\"en\" \
         target-language=\"de\"><body><trans-unit id=\"A/Text/1\"><source>Hi</source><target>",
    );
    for _ in 0..depth {
        out.push_str("<g>x\n");
    }
    for _ in 0..depth {
        out.push_str("</g>");
    }
    out.push_str("</target></trans-unit></body></file></xliff>\n");
    out
}
