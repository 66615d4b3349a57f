//! Mistakes in pages, media, settings and the bundle as a whole: hand-written HTML, phone
//! pictures, Notepad saves, renamed files. Expectations as in `acts_cases.rs`.

use super::Mistake;
use super::command_cases::{HEIC, TIFF};
use super::edits::Edit::{self, *};

const fn replace(file: &'static str, find: &'static str, with: &'static str) -> Edit {
    Replace { file, find, with }
}

const HOME: &str = "pages/index.html";
const EVENTS: &str = "pages/events.html";
const PLAN: &str = "pages/floor-plan.html";

/// Hand-written or hand-edited pages.
pub const PAGES: &[Mistake] = &[
    Mistake {
        name: "forgot the `>` of a button's start tag",
        edits: &[replace(
            HOME,
            "data-act=\"SHOW_PLAN\">Floor plan",
            "data-act=\"SHOW_PLAN\"Floor plan",
        )],
        expect: &[("page-hidden-content", "pages/index.html:19:62")],
    },
    Mistake {
        name: "wrote `data-action` for `data-act` on a button",
        edits: &[replace(
            HOME,
            "data-act=\"SHOW_PLAN\"",
            "data-action=\"SHOW_PLAN\"",
        )],
        expect: &[("act-attribute-typo", "pages/index.html:19:42")],
    },
    Mistake {
        name: "commented out a heading with `<!--` and never closed it, before the buttons",
        edits: &[replace(
            HOME,
            "    <p class=\"lead\">",
            "    <!-- <p class=\"lead\">",
        )],
        expect: &[
            ("page-hidden-content", "pages/index.html:15:5"),
            ("unused-act", "info.yaml:10:10"),
            ("unused-act", "info.yaml:18:10"),
            ("unused-act", "info.yaml:25:10"),
            ("unused-act", "info.yaml:31:10"),
            ("unused-act", "slideshow.yaml:4:10"),
        ],
    },
    Mistake {
        name: "lost the closing quote of a data-act value",
        edits: &[replace(
            HOME,
            "data-act=\"SHOW_PLAN\"",
            "data-act=\"SHOW_PLAN>",
        )],
        expect: &[("act-quoting", "pages/index.html:19:52")],
    },
    Mistake {
        name: "typed a data-act label wrong",
        edits: &[replace(
            HOME,
            "data-act=\"SHOW_PLAN\"",
            "data-act=\"SHOW_PLANS\"",
        )],
        expect: &[
            ("unknown-act", "pages/index.html:19:52"),
            ("unused-act", "info.yaml:25:10"),
        ],
    },
    Mistake {
        name: "linked to a page that does not exist",
        edits: &[replace(
            EVENTS,
            "href=\"floor-plan.html\"",
            "href=\"floorplan.html\"",
        )],
        expect: &[("broken-link", "pages/events.html:31:29")],
    },
    Mistake {
        name: "linked to the start page as `Index.html`",
        edits: &[replace(
            "pages/kids corner.html",
            "href=\"index.html\"",
            "href=\"Index.html\"",
        )],
        expect: &[("broken-link", "pages/kids corner.html:18:29")],
    },
    Mistake {
        name: "linked a picture on the desktop of the office computer",
        edits: &[replace(
            PLAN,
            "src=\"images/reading-room.jpg\"",
            "src=\"C:\\Users\\desk\\Pictures\\reading-room.jpg\"",
        )],
        expect: &[("broken-link", "pages/floor-plan.html:16:17")],
    },
    Mistake {
        name: "the stylesheet names the logo as `Logo.png`",
        edits: &[replace(
            "pages/style.css",
            "url(\"images/logo.png\")",
            "url(\"images/Logo.png\")",
        )],
        expect: &[("broken-link", "pages/style.css:31:38")],
    },
    Mistake {
        name: "used a web font from the internet",
        edits: &[replace(
            HOME,
            "  <link rel=\"stylesheet\" href=\"style.css\">",
            "  <link rel=\"stylesheet\" href=\"https://fonts.example.com/css?family=Open+Sans\">\n  \
             <link rel=\"stylesheet\" href=\"style.css\">",
        )],
        expect: &[("external-link", "pages/index.html:7:32")],
    },
    Mistake {
        name: "put a scanned TIFF picture on a page",
        edits: &[
            Write {
                file: "pages/images/reading-room.tif",
                bytes: TIFF,
            },
            replace(
                PLAN,
                "src=\"images/reading-room.jpg\"",
                "src=\"images/reading-room.tif\"",
            ),
        ],
        expect: &[("media-converted", "pages/floor-plan.html:16:17")],
    },
    Mistake {
        name: "put an iPhone photo (.HEIC) on a page",
        edits: &[
            Write {
                file: "pages/images/IMG_2041.HEIC",
                bytes: HEIC,
            },
            replace(
                PLAN,
                "src=\"images/reading-room.jpg\"",
                "src=\"images/IMG_2041.HEIC\"",
            ),
        ],
        expect: &[("media-converted", "pages/floor-plan.html:16:17")],
    },
    Mistake {
        name: "saved the start page in Notepad as ANSI (Windows-1252)",
        edits: &[SaveAsWindows1252 { file: HOME }],
        expect: &[("page-encoding", "pages/index.html:18:74")],
    },
    Mistake {
        name: "declared `<meta charset=\"windows-1252\">` copied from an old page",
        edits: &[replace(
            "pages/opening-hours.html",
            "<meta charset=\"utf-8\">",
            "<meta charset=\"windows-1252\">",
        )],
        expect: &[("page-charset", "pages/opening-hours.html:4:18")],
    },
    Mistake {
        name: "wrote the slide delay as `15 sec`",
        edits: &[replace(
            "pages/news/slide-1.html",
            "data-act-after=\"15s\"",
            "data-act-after=\"15 sec\"",
        )],
        expect: &[("bad-act-delay", "pages/news/slide-1.html:11:48")],
    },
    Mistake {
        name: "wrote the slide delay as a bare `15`",
        edits: &[replace(
            "pages/news/slide-2.html",
            "data-act-after=\"15s\"",
            "data-act-after=\"15\"",
        )],
        expect: &[("bad-act-delay", "pages/news/slide-2.html:12:49")],
    },
    Mistake {
        name: "typed the label inside `docent.trigger(...)` wrong",
        edits: &[replace(
            EVENTS,
            "docent.trigger(\"READ_EVENTS\")",
            "docent.trigger(\"READ_EVENT\")",
        )],
        expect: &[("unknown-act", "pages/events.html:11:25")],
    },
    Mistake {
        name: "deleted the hidden span that offers the act the page script triggers",
        edits: &[replace(
            EVENTS,
            "    <span data-act=\"READ_EVENTS\" hidden></span>\n",
            "",
        )],
        expect: &[
            ("trigger-not-offered", "pages/events.html:11:25"),
            ("unused-act", "info.yaml:49:10"),
        ],
    },
    Mistake {
        name: "a page script triggers the greeting, which no page offers",
        edits: &[replace(
            EVENTS,
            "docent.trigger(\"READ_EVENTS\")",
            "docent.trigger(\"WELCOME\")",
        )],
        expect: &[("trigger-not-offered", "pages/events.html:11:25")],
    },
];

/// Media judged by content, settings and the bundle as a whole.
pub const MEDIA_AND_BUNDLE: &[Mistake] = &[
    Mistake {
        name: "renamed an iPhone photo from .heic to .jpg and projected it",
        edits: &[
            Write {
                file: "media/events-poster.jpg",
                bytes: HEIC,
            },
            replace(
                "info.yaml",
                "PROJECT events-poster.png",
                "PROJECT events-poster.jpg",
            ),
        ],
        expect: &[("media-converted", "info.yaml:23:15")],
    },
    Mistake {
        name: "replaced the reading-room photo with a HEIC renamed to .jpg",
        edits: &[Write {
            file: "pages/images/reading-room.jpg",
            bytes: HEIC,
        }],
        // Converted once, noted once, at its first use.
        expect: &[("media-converted", "pages/floor-plan.html:16:17")],
    },
    Mistake {
        name: "saved the poster as PNG but named it .jpeg",
        edits: &[
            Copy {
                from: "media/events-poster.png",
                to: "media/events-poster.jpeg",
            },
            replace(
                "info.yaml",
                "PROJECT events-poster.png",
                "PROJECT events-poster.jpeg",
            ),
        ],
        expect: &[("media-misnamed", "info.yaml:23:15")],
    },
    Mistake {
        name: "wrote a new act and offered it nowhere",
        edits: &[replace(
            "info.yaml",
            "    - WAIT 20s\n    - DISPLAY_PAGE index.html\n",
            "    - WAIT 20s\n    - DISPLAY_PAGE index.html\n\n- Label: READ_RULES\n  Text:\n    - \
             Please be quiet in the reading room.\n",
        )],
        expect: &[("unused-act", "info.yaml:81:10")],
    },
    Mistake {
        name: "renamed the start page to start.html",
        edits: &[Rename {
            from: "pages/index.html",
            to: "pages/start.html",
        }],
        expect: &[
            ("no-home-page", "docent.yaml:4:7"),
            ("missing-file", "greetings.yaml:16:20"),
            ("missing-file", "info.yaml:8:20"),
            ("broken-link", "pages/kids corner.html:18:29"),
        ],
    },
    Mistake {
        name: "set `home: Index.html`",
        edits: &[replace(
            "docent.yaml",
            "home: index.html",
            "home: Index.html",
        )],
        expect: &[("miscased-file", "docent.yaml:4:7")],
    },
    Mistake {
        name: "typed the idle act's label wrong in docent.yaml",
        edits: &[replace(
            "docent.yaml",
            "idle_act: INVITE",
            "idle_act: INVTE",
        )],
        expect: &[
            ("unknown-act", "docent.yaml:17:13"),
            ("unused-act", "greetings.yaml:18:10"),
        ],
    },
    Mistake {
        name: "typed `rat:` for the speech rate",
        edits: &[replace("docent.yaml", "  rate: 150", "  rat: 150")],
        expect: &[("config-unknown-key", "docent.yaml:9:3")],
    },
    Mistake {
        name: "wrote the idle time as a bare `2`",
        edits: &[replace("docent.yaml", "  idle: 2m", "  idle: 2")],
        expect: &[("config-bad-value", "docent.yaml:16:9")],
    },
    Mistake {
        name: "wrote `idle_act:` in the same column as `kiosk:`",
        edits: &[replace(
            "docent.yaml",
            "  idle_act: INVITE",
            "idle_act: INVITE",
        )],
        expect: &[("config-unknown-key", "docent.yaml:17:1")],
    },
    Mistake {
        name: "saved the start page beside the acts files instead of in pages",
        edits: &[Rename {
            from: "pages/index.html",
            to: "index.html",
        }],
        expect: &[
            ("no-home-page", "docent.yaml:4:7"),
            ("missing-file", "greetings.yaml:16:20"),
            ("missing-file", "info.yaml:8:20"),
        ],
    },
    Mistake {
        name: "saved the acts files in pages instead of at the top",
        edits: &[
            Rename {
                from: "greetings.yaml",
                to: "pages/greetings.yaml",
            },
            Rename {
                from: "info.yaml",
                to: "pages/info.yaml",
            },
            Rename {
                from: "slideshow.yaml",
                to: "pages/slideshow.yaml",
            },
        ],
        expect: &[("no-acts", "pages/greetings.yaml:1:1")],
    },
    Mistake {
        name: "saved the tour film in pages instead of media",
        edits: &[Rename {
            from: "media/library-tour.webm",
            to: "pages/library-tour.webm",
        }],
        expect: &[("missing-file", "info.yaml:77:15")],
    },
];
