//! Texts that reach the robot other than they look in the file, and spoken texts a synthesiser
//! reads badly: each check with a broken file in, the exact code, file, line and column out,
//! and the message quoting what the robot would say. Legal variants (byte-order mark, CRLF,
//! quoted `#`, block texts) pass.

use crate::common;

use common::check::{assert_plain, bundle, check, check_all, loaded, places, yaml};
use docent_content::Severity;

fn place(code: &'static str, at: &str) -> (&'static str, String) {
    (code, at.to_owned())
}

#[test]
fn a_hash_after_a_plain_text_cuts_the_sentence_and_the_message_quotes_the_rest() {
    let acts = yaml(&[
        "- Label: TALK",
        "  Text:",
        "    - The talk is at four o'clock in Room #4 on the ground floor.",
        "    - We open at ten. # a note for staff",
        "    - \"Quoted Room #4 is fine.\"",
    ]);
    let report = check(bundle(&[("acts.yaml", &acts)]).path());
    assert_eq!(
        places(&report),
        [
            place("text-cut-by-comment", "acts.yaml:3:43"),
            place("text-cut-by-comment", "acts.yaml:4:23"),
        ]
    );
    let [cut, note] = [&report.diagnostics[0], &report.diagnostics[1]];
    assert_eq!(cut.severity, Severity::Error);
    assert!(
        cut.message
            .contains("says only: \"The talk is at four o'clock in Room\""),
        "{}",
        cut.message
    );
    assert_eq!(note.severity, Severity::Warning);
    assert_plain(&report);
}

#[test]
fn an_alternative_indented_one_space_more_is_joined_to_the_one_above() {
    let acts = yaml(&[
        "- Label: GREET",
        "  Text:",
        "    - Hello and welcome, let me help you find your way.",
        "     - Good day, and welcome to the library.",
        "    - Hi there.",
    ]);
    let report = check(bundle(&[("acts.yaml", &acts)]).path());
    assert_eq!(places(&report), [place("joined-lines", "acts.yaml:4:6")]);
    assert!(report.diagnostics[0].message.contains(
        "\"Hello and welcome, let me help you find your way. - Good day, and welcome to the library.\""
    ));
    assert!(report.diagnostics[0].is_error());
    assert!(report.bundle.is_none());
}

#[test]
fn a_missing_dash_joins_two_sentences_with_a_warning() {
    let acts = yaml(&[
        "- Label: HOURS",
        "  Text:",
        "    - We open at ten.",
        "      We close at six.",
    ]);
    let report = check(bundle(&[("acts.yaml", &acts)]).path());
    // At the line that needs its `- `, naming the line it is joined to.
    assert_eq!(places(&report), [place("joined-lines", "acts.yaml:4:7")]);
    assert_eq!(report.diagnostics[0].severity, Severity::Warning);
    assert!(report.diagnostics[0].message.contains("text of line 3"));
}

#[test]
fn word_processor_bullets_and_curly_quotes_are_named() {
    let acts = yaml(&[
        "- Label: LIST",
        "  Text:",
        "    – First sentence.",
        "    – Second sentence.",
        "- Label: CURLY",
        "  Text:",
        "    - “Welcome to the library”",
    ]);
    let report = check(bundle(&[("acts.yaml", &acts)]).path());
    assert_eq!(
        places(&report),
        [
            place("word-processor-dash", "acts.yaml:3:5"),
            place("joined-lines", "acts.yaml:4:5"),
            place("curly-quotes", "acts.yaml:7:7"),
        ]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("\"– First sentence. – Second sentence.\"")
    );
}

#[test]
fn a_no_break_space_where_yaml_needs_a_space_is_an_error_at_the_space() {
    let acts = "- Label: NB\n  Text:\n    -\u{a0}Hello\n- Label: NB2\n  Text:\u{a0}Hi\n\
                - Label: FINE\n  Text: ten\u{a0}o'clock is fine\n";
    let report = check(bundle(&[("acts.yaml", acts)]).path());
    assert_eq!(
        places(&report),
        [
            place("non-breaking-space", "acts.yaml:3:6"),
            place("non-breaking-space", "acts.yaml:5:8"),
        ]
    );
    assert_plain(&report);
}

#[test]
fn emoji_addresses_markup_placeholders_are_found_in_texts_and_say_commands() {
    let acts = yaml(&[
        "- Label: SPEECH",
        "  Text:",
        "    - Hi 😊 there",
        "    - See https://library.example.org today",
        "    - 'Hello {name}'",
        "  Cmds:",
        "    - SAY Look at <i>this</i>",
        "    - \"SAY Mail desk@library.example.org\"",
    ]);
    let report = check(bundle(&[("acts.yaml", &acts)]).path());
    assert_eq!(
        places(&report),
        [
            place("speech-emoji", "acts.yaml:3:10"),
            place("speech-address", "acts.yaml:4:11"),
            place("speech-placeholder", "acts.yaml:5:14"),
            place("speech-markup", "acts.yaml:7:19"),
            place("speech-address", "acts.yaml:8:17"),
        ]
    );
    assert!(
        report.bundle.is_none(),
        "emoji, placeholders and markup are errors"
    );
}

#[test]
fn long_texts_are_measured_at_the_configured_rate_and_limit() {
    let sentence = "This sentence has exactly ten words in it, you see. ";
    let pasted = sentence.repeat(70); // 700 words: over four minutes at 160 a minute
    let longish = sentence.repeat(10); // 100 words: 37.6 s at 160 a minute
    let acts = format!("- Label: PASTED\n  Text: {pasted}\n- Label: LONGISH\n  Text: {longish}\n");
    let report = check(bundle(&[("acts.yaml", &acts)]).path());
    assert_eq!(
        places(&report),
        [
            place("speech-too-long", "acts.yaml:2:9"),
            place("speech-too-long", "acts.yaml:4:9"),
        ]
    );
    assert!(report.diagnostics[0].is_error());
    assert!(
        report.diagnostics[0].message.contains("4 min 23 s"),
        "{}",
        report.diagnostics[0].message
    );
    assert_eq!(report.diagnostics[1].severity, Severity::Warning);
    // Faster speech and a higher limit make the longish text fine.
    let settings = "speech:\n  rate: 200\n  max_seconds: 45\n";
    let acts = format!("- Label: LONGISH\n  Text: {longish}\n");
    let report = check(bundle(&[("acts.yaml", &acts), ("docent.yaml", settings)]).path());
    assert_eq!(places(&report), []);
}

#[test]
fn a_misspelt_context_gets_a_did_you_mean_without_declared_contexts() {
    let acts = yaml(&[
        "- Label: A",
        "  Text: Hello",
        "  TextChild: Hi",
        "- Label: B",
        "  Text: Bye",
        "  TextChild: Bye bye",
        "- Label: C",
        "  Text: Look",
        "  TextChlid: Look, kids",
    ]);
    let report = check(bundle(&[("acts.yaml", &acts)]).path());
    assert_eq!(places(&report), [place("context-typo", "acts.yaml:9:3")]);
    assert!(
        report.diagnostics[0]
            .message
            .contains("Did you mean `TextChild`?")
    );
}

/// Without `contexts:`, a context one act alone uses (the paper's `TextGroup`, `TextFormally`)
/// is meant; one not written as `Text` and a capitalised word is most likely a slip.
#[test]
fn a_lonely_context_is_fine_and_a_badly_written_one_is_warned_about() {
    let fig4 = yaml(&[
        "- Label: WHERE_FROM",
        "  Text: Where do you come from?",
        "  TextGroup: Where are you from?",
        "  TextFormally: May I ask from where you are?",
        "- Label: OK",
        "  Text: OK!",
    ]);
    assert_eq!(places(&check(bundle(&[("acts.yaml", &fig4)]).path())), []);
    let sloppy = fig4.replace("TextFormally", "Textformally");
    let report = check(bundle(&[("acts.yaml", &sloppy)]).path());
    assert_eq!(places(&report), [place("context-typo", "acts.yaml:4:3")]);
    assert!(
        report.diagnostics[0]
            .message
            .contains("`Textformally` does not read as a context name"),
        "{}",
        report.diagnostics[0].message
    );
}

#[test]
fn acts_nothing_triggers_are_warned_about() {
    let dir = bundle(&[
        (
            "acts.yaml",
            &yaml(&[
                "- Label: OFFERED",
                "  Text: Hi",
                "- Label: FOR_THE_OPERATOR",
                "  Group: Small talk",
                "  Text: Hi",
                "- Label: FORGOTTEN",
                "  Text: Hi",
                "- Label: IDLE",
                "  Text: Anyone there?",
            ]),
        ),
        ("docent.yaml", "kiosk:\n  idle_act: IDLE\n"),
        (
            "pages/index.html",
            "<button data-act=\"OFFERED\">Hi</button>",
        ),
    ]);
    let report = check_all(dir.path());
    assert_eq!(places(&report), [place("unused-act", "acts.yaml:6:10")]);
    assert!(report.diagnostics[0].message.contains("`FORGOTTEN`"));
}

#[test]
fn files_not_saved_as_utf8_name_the_encoding_and_the_character() {
    let windows = b"- Label: A\n  Text: \xd6ffnungszeiten\n".to_vec();
    let mut utf16 = vec![0xFF, 0xFE];
    utf16.extend("- Label: A\n".encode_utf16().flat_map(u16::to_le_bytes));
    let dir = bundle(&[]);
    std::fs::write(dir.path().join("acts.yaml"), windows).expect("write");
    std::fs::write(dir.path().join("more.yaml"), utf16).expect("write");
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            place("file-encoding", "acts.yaml:2:9"),
            place("file-encoding", "more.yaml:1:1"),
        ]
    );
    assert!(report.diagnostics[0].message.contains("probably `Ö`"));
    assert!(report.diagnostics[1].message.contains("UTF-16"));
}

#[test]
fn an_unreadable_file_is_the_only_problem_reported_for_it() {
    let mut utf16 = vec![0xFF, 0xFE];
    utf16.extend(
        "- Label: HELLO\n  Text: Hi\n"
            .encode_utf16()
            .flat_map(u16::to_le_bytes),
    );
    let dir = bundle(&[
        ("pages/index.html", "<button data-act=\"HELLO\">Hi</button>"),
        (
            "docent.yaml",
            "contexts: [TextChild\nkiosk:\n  idle_act: OTHER\n",
        ),
        ("other.yaml", "- Label: OTHER\n  Text: Anyone there?\n"),
    ]);
    std::fs::write(dir.path().join("acts.yaml"), utf16).expect("write");
    // No `unknown-act` for the page's HELLO (it is in the file that cannot be read), and no
    // `unused-act` for OTHER (the idle act, in the settings that cannot be read).
    let report = check_all(dir.path());
    assert_eq!(
        places(&report),
        [
            place("file-encoding", "acts.yaml:1:1"),
            place("config-syntax", "docent.yaml:1:11"),
        ]
    );
}

#[test]
fn a_byte_order_mark_and_windows_line_ends_pass_and_no_carriage_return_is_spoken() {
    let acts = "\u{feff}- Label: A\r\n  Text:\r\n    - |\r\n      Two lines\r\n      of text\r\n    \
                - \"Quoted over\r\n      two lines\"\r\n  Cmds:\r\n    - SAY Later\r\n";
    let bundle = loaded(check(bundle(&[("acts.yaml", acts)]).path()));
    let act = bundle.act("A").expect("act");
    let texts: Vec<&str> = act.variants[0]
        .alternatives
        .iter()
        .map(|a| a.value.as_str())
        .collect();
    assert_eq!(texts, ["Two lines\nof text\n", "Quoted over two lines"]);
    assert_eq!(act.commands[0].value.arg.as_deref(), Some("Later"));
    assert_eq!(act.pos.line, 1);
}

#[test]
fn texts_with_these_characters_in_normal_use_pass() {
    let acts = yaml(&[
        "- Label: FINE",
        "  Text:",
        "    - \"Room #4 is on the left.\"",
        "    - It is 20 °C; tickets cost 5 € (10 % off) & kids go free.",
        "    - The years 1980–1990 – a decade of change.",
        "    - >",
        "      A long text folded",
        "      over lines on purpose.",
    ]);
    let report = check(bundle(&[("acts.yaml", &acts)]).path());
    assert_eq!(places(&report), []);
}
