//! The tutorial's mistakes with files, pages and settings (docs/GETTING-STARTED.md): a page,
//! film or acts file saved in the wrong folder or under a near name, a button whose attribute
//! or `>` went wrong, a label in the wrong case, settings not indented under their section.
//! Each told at the file, line and column that causes it (helpers in `getting_started`).

use crate::common;
use crate::getting_started::{ACTS, HOME, hello_museum, report_of, says, the_one};

use common::check::places;

#[test]
fn a_home_page_saved_beside_acts_yaml_is_told_there_with_where_to_move_it() {
    let dir = hello_museum(&[("index.html", HOME)], &["pages/index.html"]);
    let report = report_of(dir.path());
    let told = the_one(&report, "no-home-page", "index.html:1:1");
    says(told, "There is no file `pages/index.html`.");
    says(
        told,
        "There is a file `index.html` at the top of the bundle, beside the acts files: move it \
         into the `pages` folder.",
    );
}

#[test]
fn a_home_page_saved_in_media_or_one_folder_too_deep_is_told_where_it_is() {
    for (saved, move_to) in [
        ("media/index.html", "move it into the `pages` folder"),
        ("page/index.html", "move it into the `pages` folder"),
        ("pages/pages/index.html", "move it to `pages/index.html`"),
    ] {
        let dir = hello_museum(&[(saved, HOME)], &["pages/index.html"]);
        let report = report_of(dir.path());
        let told = the_one(&report, "no-home-page", &format!("{saved}:1:1"));
        says(told, &format!("There is a file `{saved}`: {move_to}."));
    }
}

#[test]
fn a_page_or_film_an_act_shows_saved_in_the_wrong_folder_is_told_at_the_command() {
    let acts = format!(
        "{ACTS}\n- Label: MAP\n  Cmds:\n    - DISPLAY_PAGE map.html\n\n- Label: FILM\n  Cmds:\n    \
         - PROJECT film.webm\n"
    );
    let dir = hello_museum(
        &[
            ("acts.yaml", &acts),
            ("map.html", "<!doctype html><title>Map</title>"),
            (
                "pages/film.webm",
                "not looked at: the film is in the wrong folder",
            ),
        ],
        &[],
    );
    let report = report_of(dir.path());
    let missing: Vec<(&'static str, String)> = places(&report)
        .into_iter()
        .filter(|(code, _)| *code == "missing-file")
        .collect();
    assert_eq!(
        missing,
        [
            ("missing-file", "acts.yaml:12:20".to_owned()),
            ("missing-file", "acts.yaml:16:15".to_owned()),
        ]
    );
    says(
        &report.diagnostics[0],
        "There is a file `map.html` at the top of the bundle, beside the acts files: move it \
         into the `pages` folder.",
    );
    let film = report
        .diagnostics
        .iter()
        .find(|d| d.line == 16)
        .expect("the film");
    says(
        film,
        "There is a file `pages/film.webm`: move it into the `media` folder.",
    );
}

#[test]
fn a_label_written_in_the_wrong_case_on_the_page_gets_the_right_one_suggested() {
    for written in ["welcome", "Welcome"] {
        let home = HOME.replace("data-act=\"WELCOME\"", &format!("data-act=\"{written}\""));
        let dir = hello_museum(&[("pages/index.html", &home)], &[]);
        let report = report_of(dir.path());
        let told = the_one(&report, "unknown-act", "pages/index.html:9:35");
        says(told, "Did you mean `WELCOME`?");
    }
    let home = HOME.replace(
        "</body>",
        "<script>docent.trigger('opening_hours');</script>\n</body>",
    );
    let dir = hello_museum(&[("pages/index.html", &home)], &[]);
    let report = report_of(dir.path());
    let told = the_one(&report, "unknown-act", "pages/index.html:11:25");
    says(told, "Did you mean `OPENING_HOURS`?");
}

#[test]
fn step_six_settings_not_indented_under_their_section_are_told_so() {
    let dir = hello_museum(&[("docent.yaml", "corpus:\nrecord: none\n")], &[]);
    let report = report_of(dir.path());
    let told = the_one(&report, "config-unknown-key", "docent.yaml:2:1");
    says(told, "`record` is a setting of `corpus:` above");
    says(told, "Indent it by two spaces, under `corpus:`.");

    let dir = hello_museum(&[("docent.yaml", "corpus: record: none\n")], &[]);
    let report = report_of(dir.path());
    let told = the_one(&report, "config-syntax", "docent.yaml:1:15");
    says(
        told,
        "Two settings are written on one line: `corpus:` and `record: none`.",
    );
    says(told, "put `record: none` on the next line");
}

#[test]
fn a_button_with_an_attribute_like_data_act_is_told_at_that_attribute() {
    for written in ["data-action", "data_act", "act", "data-acts"] {
        let home = HOME.replace("data-act=\"WELCOME\"", &format!("{written}=\"WELCOME\""));
        let dir = hello_museum(&[("pages/index.html", &home)], &[]);
        let report = report_of(dir.path());
        let told = the_one(&report, "act-attribute-typo", "pages/index.html:9:25");
        assert!(!told.is_error());
        says(
            told,
            &format!("`{written}` is not an attribute Docent reads"),
        );
        says(told, "Write `data-act=\"WELCOME\"` instead");
    }
    // Beside a real `data-act`, another attribute is the page's own business.
    let home = HOME.replace(
        "data-act=\"WELCOME\"",
        "data-act=\"WELCOME\" data-action=\"greet\"",
    );
    let dir = hello_museum(&[("pages/index.html", &home)], &[]);
    assert!(report_of(dir.path()).diagnostics.is_empty());
}

#[test]
fn acts_yaml_saved_in_pages_is_told_there_and_the_page_is_not_blamed() {
    let dir = hello_museum(&[("pages/acts.yaml", ACTS)], &["acts.yaml"]);
    let report = report_of(dir.path());
    let told = the_one(&report, "no-acts", "pages/acts.yaml:1:1");
    says(
        told,
        "`acts.yaml` is in the `pages` folder, where Docent does not look for acts.",
    );
    says(told, "Move it up into the bundle folder");
    says(told, "next to the `pages` folder.");
}

#[test]
fn a_home_page_saved_as_index_htm_or_index_html_capitalised_is_told_at_that_file() {
    let dir = hello_museum(&[("pages/index.htm", HOME)], &["pages/index.html"]);
    let report = report_of(dir.path());
    let told = the_one(&report, "no-home-page", "pages/index.htm:1:1");
    says(told, "Did you mean `index.htm`?");

    let dir = hello_museum(&[("pages/Index.html", HOME)], &["pages/index.html"]);
    let report = report_of(dir.path());
    let told = the_one(&report, "miscased-file", "pages/Index.html:1:1");
    says(told, "The file is called `Index.html`");
}

#[test]
fn a_button_tag_without_its_closing_angle_is_told_where_the_angle_belongs() {
    let home = HOME.replace("data-act=\"WELCOME\">Say", "data-act=\"WELCOME\"Say");
    let dir = hello_museum(&[("pages/index.html", &home)], &[]);
    let report = report_of(dir.path());
    let told = the_one(&report, "page-hidden-content", "pages/index.html:9:43");
    says(told, "This `<button>` tag has no `>` here");
    says(told, "(`Say hello</button`)");
    says(told, "Type `>` right here.");
}
