//! The schema of the kiosk's own screens: `kiosk: attract:` (and the same in a schedule
//! range) and `schedule:`. Keys from the loader's lists in `config_file/attract.rs` and
//! `config_file/schedule.rs`; the patterns follow their grammar of days and hours.

use serde_json::{Value, json};

use crate::config_file::attract::ATTRACT_KEYS;
use crate::config_file::schedule::{OPEN_KEYS, SCHEDULE_KEYS, SPECIAL_DAY_KEYS};
use crate::schema::{duration, section, words};

const DAY: &str = r"([Mm][Oo][Nn]|[Tt][Uu][Ee]|[Ww][Ee][Dd]|[Tt][Hh][Uu]|[Ff][Rr][Ii]|[Ss][Aa][Tt]|[Ss][Uu][Nn])[A-Za-z]*";
const TIME: &str = r"\d{1,2}:\d\d";

/// `attract:`: after, pages, every, act.
pub(super) fn attract() -> Value {
    section(
        ATTRACT_KEYS,
        |key| match key {
            "after" => duration(
                "How long the touchscreen waits without a touch before the attract loop \
                 starts, e.g. `3m` (2m unless set).",
            ),
            "every" => duration(
                "How long each attract page stays on screen, e.g. `10s` (the default); with \
                 only an act, how often it is repeated (once unless set).",
            ),
            "pages" => {
                let page = words("A page under pages/, e.g. `attract/a.html`.");
                json!({
                    "description": "The pages the attract loop shows in turn.",
                    "anyOf": [page, { "type": "array", "items": page, "minItems": 1 }],
                })
            }
            _ => json!({
                "type": "string",
                "pattern": r"^\S+$",
                "description": "The label of the act triggered when the loop starts, e.g. \
                                `INVITE`.",
            }),
        },
        "The attract loop: after a time without a touch the kiosk shows pages in turn or \
         triggers an act, until the first touch, which returns to the home page.",
    )
}

/// `schedule:`: closed, open, special_days.
pub(super) fn schedule() -> Value {
    let hours = json!({
        "type": "string",
        "pattern": format!(r"^\s*{TIME}\s*-\s*{TIME}\s*(,\s*{TIME}\s*-\s*{TIME}\s*)*$"),
        "description": "Time ranges on the 24-hour clock, e.g. `09:00-17:00` or \
                        `10:00-12:00, 13:00-18:00`.",
    });
    let days = json!({
        "description": "Weekdays: `Mon-Fri`, `Sat, Sun`, `daily`, or a list of them.",
        "anyOf": [
            { "type": "string", "pattern": format!(r"^\s*([Dd]aily|{DAY}(\s*-\s*{DAY})?)(\s*,\s*{DAY}(\s*-\s*{DAY})?)*\s*$") },
            { "type": "array", "items": { "type": "string" } },
        ],
    });
    let range_extra = |key: &str| match key {
        "home" => words("The home page in these hours, e.g. `school/index.html`."),
        _ => attract(),
    };
    let open = section(
        OPEN_KEYS,
        |key| match key {
            "days" => days.clone(),
            "hours" => hours.clone(),
            other => range_extra(other),
        },
        "Opening hours on some weekdays.",
    );
    let special = section(
        SPECIAL_DAY_KEYS,
        |key| match key {
            "date" => json!({
                "type": "string",
                "pattern": r"^\d{4}-\d\d-\d\d$",
                "description": "The day, year-month-day, e.g. `2025-12-24`.",
            }),
            "hours" => json!({
                "description": "Its opening hours, or `closed` all day.",
                "anyOf": [hours.clone(), { "const": "closed" }],
            }),
            other => range_extra(other),
        },
        "A date whose hours differ from its weekday's.",
    );
    section(
        SCHEDULE_KEYS,
        |key| match key {
            "closed" => words("The page under pages/ shown outside opening hours."),
            "open" => json!({
                "type": "array",
                "items": open.clone(),
                "description": "Opening hours by weekday, each with its own home page and \
                                attract loop if wanted.",
            }),
            _ => json!({
                "type": "array",
                "items": special.clone(),
                "description": "Dates that differ from their weekday (holidays, late nights).",
            }),
        },
        "Opening hours, evaluated by the kiosk's own clock: outside them the kiosk shows the \
         `closed` page.",
    )
}
