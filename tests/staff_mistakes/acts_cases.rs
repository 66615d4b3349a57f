//! Mistakes in the texts of the acts files: Word and Notepad habits, copy-paste, YAML traps.
//! Each expectation is where the author made the mistake, as (code, `file:line:column`); the
//! first is the mistake itself, any others are its real consequences.

use super::Mistake;
use super::edits::Edit::{self, *};

const fn replace(file: &'static str, find: &'static str, with: &'static str) -> Edit {
    Replace { file, find, with }
}

const G: &str = "greetings.yaml";
const I: &str = "info.yaml";
const S: &str = "slideshow.yaml";

/// Word and Notepad habits.
pub const WORD_AND_NOTEPAD: &[Mistake] = &[
    Mistake {
        name: "typed a greeting in Word, which curled the quotes around it",
        edits: &[replace(
            G,
            "    - Good day, and welcome to the library. How can I help you?",
            "    - “Good day, and welcome to the library. How can I help you?”",
        )],
        expect: &[("curly-quotes", "greetings.yaml:9:7")],
    },
    Mistake {
        name: "pasted a Word list with en-dash bullets",
        edits: &[replace(
            G,
            "    - Goodbye, and happy reading!\n    - Thank you",
            "    – Goodbye, and happy reading!\n    – Thank you",
        )],
        expect: &[("word-processor-dash", "greetings.yaml:29:5")],
    },
    Mistake {
        name: "pasted a single alternative with an em-dash bullet from an e-mail",
        edits: &[replace(
            I,
            "    - Come and see the reading tent!",
            "    — Come and see the reading tent!",
        )],
        expect: &[("word-processor-dash", "info.yaml:35:5")],
    },
    Mistake {
        name: "a no-break space after the dash, pasted from an e-mail",
        edits: &[replace(
            G,
            "    - Looking for something?",
            "    -\u{a0}Looking for something?",
        )],
        expect: &[("non-breaking-space", "greetings.yaml:20:6")],
    },
    Mistake {
        name: "indented an alternative with no-break spaces copied from a web page",
        edits: &[replace(
            G,
            "    - Hello everyone,",
            "\u{a0}\u{a0}\u{a0}\u{a0}- Hello everyone,",
        )],
        expect: &[("non-breaking-space", "greetings.yaml:12:1")],
    },
    Mistake {
        name: "wrote `Room #2` in a text without quotes",
        edits: &[replace(
            I,
            "    - \"On Tuesday at four o'clock there is story time in Room #2, for children from four years.\"",
            "    - On Tuesday at four o'clock there is story time in Room #2, for children from four years.",
        )],
        expect: &[("text-cut-by-comment", "info.yaml:51:62")],
    },
    Mistake {
        name: "saved the greetings in Notepad as ANSI (Windows-1252) after adding `À bientôt`",
        edits: &[
            replace(G, "See you soon!", "À bientôt!"),
            SaveAsWindows1252 { file: G },
        ],
        // The file's acts are unknown until it is saved again: nothing else is blamed on it.
        expect: &[("file-encoding", "greetings.yaml:30:33")],
    },
    Mistake {
        name: "saved the acts file in Notepad as Unicode (UTF-16)",
        edits: &[SaveAsUtf16 { file: I }],
        expect: &[
            // The file's acts are unknown until it is saved again: the pages' buttons are not
            // blamed for naming them.
            ("file-encoding", "info.yaml:1:1"),
        ],
    },
    Mistake {
        name: "indented an alternative with a tab",
        edits: &[replace(
            I,
            "    - Please follow me to the children's corner.",
            "\t- Please follow me to the children's corner.",
        )],
        expect: &[("yaml-tab", "info.yaml:60:1")],
    },
];

/// Copy and paste from documents, chats, web sites and other acts.
pub const COPY_PASTE: &[Mistake] = &[
    Mistake {
        name: "pasted the library rules document into one text",
        edits: &[PasteDocument {
            file: I,
            find: "    - The children's corner has picture books, comics and a reading tent.",
            words: 700,
        }],
        expect: &[("speech-too-long", "info.yaml:33:7")],
    },
    Mistake {
        name: "added a smiling emoji to a greeting",
        edits: &[replace(
            G,
            "    - Hi there! I can",
            "    - Hi there! 😊 I can",
        )],
        expect: &[("speech-emoji", "greetings.yaml:10:17")],
    },
    Mistake {
        name: "pasted the library's web address into a goodbye",
        edits: &[replace(
            G,
            "See you soon!",
            "More at https://riverside-library.example.org",
        )],
        expect: &[("speech-address", "greetings.yaml:30:41")],
    },
    Mistake {
        name: "pasted the front desk's e-mail address into a SAY",
        edits: &[replace(
            I,
            "    - SAY Here we are. Enjoy your books!",
            "    - SAY Questions? Write to desk@riverside-library.example.org",
        )],
        expect: &[("speech-address", "info.yaml:67:31")],
    },
    Mistake {
        name: "pasted a sentence with HTML bold from the web site",
        edits: &[replace(
            I,
            "    - This is the floor plan.",
            "    - This is the <b>floor plan</b>.",
        )],
        expect: &[("speech-markup", "info.yaml:27:19")],
    },
    Mistake {
        name: "pasted Markdown bold from a chat message",
        edits: &[replace(
            G,
            "    - Hello everyone, and welcome",
            "    - Hello everyone, and **welcome**",
        )],
        expect: &[("speech-markup", "greetings.yaml:12:27")],
    },
    Mistake {
        name: "kept the `{name}` placeholder of a mail-merge template",
        edits: &[replace(
            G,
            "    - Goodbye, and happy",
            "    - Goodbye {name}, and happy",
        )],
        expect: &[("speech-placeholder", "greetings.yaml:29:15")],
    },
    Mistake {
        name: "left `[ROOM]` for a colleague to fill in",
        edits: &[replace(
            I,
            "story time in Room #2, for children",
            "story time in Room [ROOM], for children",
        )],
        expect: &[("speech-placeholder", "info.yaml:51:63")],
    },
    Mistake {
        name: "copied an act to make a new one and forgot to rename it",
        edits: &[replace(
            S,
            "- Label: END_SLIDESHOW\n  Cmds:\n    - DISPLAY_PAGE index.html\n",
            "- Label: END_SLIDESHOW\n  Cmds:\n    - DISPLAY_PAGE index.html\n\n\
             - Label: SHOW_HOME\n  Cmds:\n    - DISPLAY_PAGE index.html\n",
        )],
        expect: &[
            ("duplicate-label", "slideshow.yaml:18:10"),
            ("duplicate-label", "info.yaml:6:10"),
        ],
    },
    Mistake {
        name: "pasted an alternative indented one space more",
        edits: &[replace(
            G,
            "    - Good day, and welcome",
            "     - Good day, and welcome",
        )],
        expect: &[("joined-lines", "greetings.yaml:9:6")],
    },
    Mistake {
        name: "forgot the dash of the second alternative",
        edits: &[replace(
            G,
            "    - Thank you for your visit.",
            "      Thank you for your visit.",
        )],
        expect: &[("joined-lines", "greetings.yaml:30:7")],
    },
    Mistake {
        name: "typed the dash of an alternative without the space after it",
        edits: &[replace(
            G,
            "    - Thank you for your visit.",
            "    -Thank you for your visit.",
        )],
        expect: &[("yaml-syntax", "greetings.yaml:30:5")],
    },
    Mistake {
        name: "typed the dash of the only text without the space after it",
        edits: &[replace(
            I,
            "    - Here are our opening hours.",
            "    -Here are our opening hours.",
        )],
        expect: &[("dash-without-space", "info.yaml:12:5")],
    },
];

/// What YAML does to text that looks fine.
pub const YAML_TRAPS: &[Mistake] = &[
    Mistake {
        name: "wrote `Note: ...` in a list of texts without quotes",
        edits: &[replace(
            I,
            "    - This is the floor plan.",
            "    - Note: this is the floor plan.",
        )],
        expect: &[("bad-value", "info.yaml:27:7")],
    },
    Mistake {
        name: "wrote `Note: ...` right after `TextChild:` without quotes",
        edits: &[replace(
            I,
            "  TextChild:\n    - The library is open every day except Sunday.",
            "  TextChild: Note: the library is closed on Sunday.",
        )],
        expect: &[("yaml-syntax", "info.yaml:46:18")],
    },
    Mistake {
        name: "answered `Yes` without quotes",
        edits: &[replace(G, "    - \"Yes.\"", "    - Yes")],
        expect: &[("unquoted-scalar", "greetings.yaml:40:7")],
    },
    Mistake {
        name: "wrote the label NO without quotes",
        edits: &[replace(G, "- Label: \"NO\"", "- Label: NO")],
        expect: &[("unquoted-scalar", "greetings.yaml:43:10")],
    },
    Mistake {
        name: "put `it's` inside single quotes",
        edits: &[replace(
            I,
            "    - Follow me, it's this way!",
            "    - 'Follow me, it's this way!'",
        )],
        expect: &[("yaml-syntax", "info.yaml:62:22")],
    },
    Mistake {
        name: "forgot the closing double quote",
        edits: &[replace(
            G,
            "just touch my screen.\"",
            "just touch my screen.",
        )],
        expect: &[("yaml-syntax", "greetings.yaml:21:7")],
    },
    Mistake {
        name: "forgot the closing bracket of the contexts list",
        edits: &[replace(
            "docent.yaml",
            "contexts: [TextChild, TextGroup]",
            "contexts: [TextChild, TextGroup",
        )],
        // The settings cannot be read: no warning follows from the defaults used meanwhile.
        expect: &[("config-syntax", "docent.yaml:5:11")],
    },
    Mistake {
        name: "indented `Cmds:` by three spaces instead of two",
        edits: &[replace(
            G,
            "    - Bye bye! Come back for story time!\n  Cmds:",
            "    - Bye bye! Come back for story time!\n   Cmds:",
        )],
        expect: &[("yaml-syntax", "greetings.yaml:33:4")],
    },
    Mistake {
        name: "typed `Lable` instead of `Label`",
        edits: &[replace(G, "- Label: INVITE", "- Lable: INVITE")],
        expect: &[
            ("unknown-key", "greetings.yaml:18:3"),
            ("missing-label", "greetings.yaml:18:3"),
            ("unknown-act", "docent.yaml:17:13"),
        ],
    },
    Mistake {
        name: "typed `TextChlid` in a bundle with contexts",
        edits: &[replace(
            G,
            "  TextChild:\n    - Bye bye!",
            "  TextChlid:\n    - Bye bye!",
        )],
        expect: &[("unknown-context", "greetings.yaml:31:3")],
    },
    Mistake {
        name: "typed `TextChlid` in a bundle without contexts",
        edits: &[
            replace("docent.yaml", "contexts: [TextChild, TextGroup]\n", ""),
            replace(
                G,
                "  TextChild:\n    - Bye bye!",
                "  TextChlid:\n    - Bye bye!",
            ),
        ],
        expect: &[("context-typo", "greetings.yaml:31:3")],
    },
    Mistake {
        name: "typed `Cmd:` instead of `Cmds:`",
        edits: &[replace(
            G,
            "    - Hello! Do you like stories? Touch my screen and I'll show you where the picture books are.\n  Cmds:",
            "    - Hello! Do you like stories? Touch my screen and I'll show you where the picture books are.\n  Cmd:",
        )],
        expect: &[("unknown-key", "greetings.yaml:15:3")],
    },
    Mistake {
        name: "quoted a text with a colon in the editor's curly quotes",
        edits: &[replace(
            G,
            "    - \"Need help? I know where every book is: just touch my screen.\"",
            "    - “Need help? I know where every book is: just touch my screen.”",
        )],
        expect: &[("bad-value", "greetings.yaml:21:7")],
    },
    Mistake {
        name: "typed `-Label:` without the space after the dash",
        edits: &[replace(G, "- Label: INVITE", "-Label: INVITE")],
        expect: &[("yaml-syntax", "greetings.yaml:18:1")],
    },
    Mistake {
        name: "started an act with `Label:` and no dash",
        edits: &[replace(G, "- Label: INVITE", "Label: INVITE")],
        expect: &[("yaml-syntax", "greetings.yaml:18:1")],
    },
    Mistake {
        name: "wrote the first alternative without its dash",
        edits: &[replace(
            G,
            "    - Looking for something?",
            "    Looking for something?",
        )],
        // The quoted text below stops YAML, which first took the `- ` lines as one text.
        expect: &[("yaml-syntax", "greetings.yaml:20:5")],
    },
    Mistake {
        name: "left the dash off an alternative between two others",
        edits: &[replace(
            G,
            "    - Good day, and welcome",
            "    Good day, and welcome",
        )],
        expect: &[("yaml-syntax", "greetings.yaml:9:5")],
    },
    Mistake {
        name: "typed `Text` without its colon",
        edits: &[replace(
            G,
            "- Label: INVITE\n  Text:\n",
            "- Label: INVITE\n  Text\n",
        )],
        expect: &[("yaml-syntax", "greetings.yaml:19:3")],
    },
    Mistake {
        name: "forgot the `Text:` line under a label",
        edits: &[replace(
            G,
            "- Label: INVITE\n  Text:\n",
            "- Label: INVITE\n",
        )],
        expect: &[("yaml-syntax", "greetings.yaml:19:5")],
    },
];
