//! The argument of the built-in `HIGHLIGHT` verb: one or more areas of the projected image to
//! light in white on black, separated by `;`. Each area is `left top width height`, fractions
//! of the projected width and height, optionally followed by its shape, `rect` (the default)
//! or `ellipse`: `HIGHLIGHT 0.10 0.20 0.35 0.25; 0.6 0.6 0.2 0.2 ellipse`. `HIGHLIGHT` alone
//! clears the projector. The projector page gets the parsed areas (`content::Args`).

/// How a HIGHLIGHT argument is written, for messages.
pub const HIGHLIGHT_USAGE: &str = "HIGHLIGHT needs an area as four fractions of the projected \
                                   image, `left top width height`, each from 0 to 1, e.g. \
                                   `HIGHLIGHT 0.10 0.20 0.35 0.25`; add `ellipse` after the \
                                   numbers for an oval, separate several areas with `;`, and \
                                   write `HIGHLIGHT` alone to turn the light off.";

/// Slack for sums of decimal fractions such as `0.7 + 0.3`.
const EPSILON: f64 = 1e-9;

/// The outline of a lit area.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Shape {
    /// `rect` (the default): a rectangle.
    Rect,
    /// `ellipse`: the ellipse inside the rectangle.
    Ellipse,
}

/// One lit area, in fractions of the projected width (`left`, `width`) and height.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Area {
    /// Distance from the left edge.
    pub left: f64,
    /// Distance from the top edge.
    pub top: f64,
    /// Width, above 0.
    pub width: f64,
    /// Height, above 0.
    pub height: f64,
    /// Rectangle or ellipse.
    pub shape: Shape,
}

/// A problem in a HIGHLIGHT argument: its byte offset into the argument and what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct HighlightProblem {
    /// Byte offset into the argument where the problem is.
    pub offset: usize,
    /// The message for people.
    pub message: String,
}

/// The areas of a HIGHLIGHT argument (empty for no argument: the light goes off), or every
/// problem found, at most one per area.
pub fn parse_highlight(arg: &str) -> Result<Vec<Area>, Vec<HighlightProblem>> {
    if arg.trim().is_empty() {
        return Ok(Vec::new());
    }
    let mut areas = Vec::new();
    let mut problems = Vec::new();
    let separators: Vec<usize> = arg.match_indices(';').map(|(i, _)| i).collect();
    let mut start = 0;
    for (n, part) in arg.split(';').enumerate() {
        let words = words_with_offsets(part, start);
        if words.is_empty() {
            // Point at a `;` next to the empty area: the one after it, or else the one before.
            let at = separators.get(n).or(separators.last()).copied();
            problems.push(HighlightProblem {
                offset: at.unwrap_or(start),
                message: format!(
                    "There is no area between these `;`. Remove the extra `;`. {HIGHLIGHT_USAGE}"
                ),
            });
        } else {
            match area(&words) {
                Ok(area) => areas.push(area),
                Err(problem) => problems.push(problem),
            }
        }
        start += part.len() + 1;
    }
    if problems.is_empty() {
        Ok(areas)
    } else {
        Err(problems)
    }
}

/// One area from its words (offsets into the whole argument).
fn area(words: &[(usize, &str)]) -> Result<Area, HighlightProblem> {
    let problem = |offset: usize, message: String| HighlightProblem { offset, message };
    let (numbers, shape) = match words {
        [n @ .., (offset, word)] if n.len() == 4 && !is_number(word) => {
            let shape = match *word {
                "rect" => Shape::Rect,
                "ellipse" => Shape::Ellipse,
                _ => {
                    return Err(problem(
                        *offset,
                        format!(
                            "`{word}` is not a shape. After the four numbers write `ellipse` \
                             for an oval, or nothing (or `rect`) for a rectangle."
                        ),
                    ));
                }
            };
            (n, shape)
        }
        n if n.len() == 4 => (n, Shape::Rect),
        _ => {
            return Err(problem(
                words[0].0,
                format!(
                    "Found {} value(s) where an area needs four numbers. {HIGHLIGHT_USAGE}",
                    words.len()
                ),
            ));
        }
    };
    let mut values = [0.0; 4];
    const NAMES: [&str; 4] = ["left", "top", "width", "height"];
    for (i, &(offset, word)) in numbers.iter().enumerate() {
        let name = NAMES[i];
        let value = match word.parse::<f64>() {
            Ok(v) if v.is_finite() => v,
            _ => {
                return Err(problem(
                    offset,
                    format!("`{word}` is not a number. {HIGHLIGHT_USAGE}"),
                ));
            }
        };
        let size = i >= 2;
        if !(0.0..=1.0).contains(&value) || (size && value == 0.0) {
            let range = if size {
                "above 0 and at most 1"
            } else {
                "from 0 to 1"
            };
            return Err(problem(
                offset,
                format!(
                    "The {name} `{word}` must be a fraction of the projected image {range}, \
                     e.g. 0.25 for a quarter."
                ),
            ));
        }
        values[i] = value;
    }
    let [left, top, width, height] = values;
    for (start, size, i, edge) in [(left, width, 2, "right"), (top, height, 3, "bottom")] {
        if start + size > 1.0 + EPSILON {
            let (from, to) = (NAMES[i - 2], NAMES[i]);
            return Err(problem(
                numbers[i].0,
                format!(
                    "The area reaches past the {edge} edge: {from} {start} plus {to} {size} is \
                     more than 1. Make the {to} at most {}.",
                    round(1.0 - start)
                ),
            ));
        }
    }
    Ok(Area {
        left,
        top,
        width,
        height,
        shape,
    })
}

fn is_number(word: &str) -> bool {
    word.parse::<f64>().is_ok()
}

/// `x` without the noise of binary fractions (`0.30000000000000004` → `0.3`).
fn round(x: f64) -> f64 {
    (x * 1e6).round() / 1e6
}

/// The words of `s` with their byte offsets, shifted by `base`.
pub(crate) fn words_with_offsets(s: &str, base: usize) -> Vec<(usize, &str)> {
    let mut words = Vec::new();
    let mut rest = s;
    let mut offset = base;
    while let Some(start) = rest.find(|c: char| !c.is_whitespace()) {
        let tail = &rest[start..];
        let end = tail.find(char::is_whitespace).unwrap_or(tail.len());
        words.push((offset + start, &tail[..end]));
        offset += start + end;
        rest = &tail[end..];
    }
    words
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(left: f64, top: f64, width: f64, height: f64) -> Area {
        Area {
            left,
            top,
            width,
            height,
            shape: Shape::Rect,
        }
    }

    /// The offsets and the start of the messages of the problems in `arg`.
    fn problems(arg: &str) -> Vec<(usize, String)> {
        let problems = parse_highlight(arg).expect_err(arg);
        problems
            .into_iter()
            .map(|p| (p.offset, p.message.chars().take(24).collect()))
            .collect()
    }

    #[test]
    fn one_area_is_four_fractions() {
        assert_eq!(
            parse_highlight("0.10 0.20 0.35 0.25"),
            Ok(vec![rect(0.10, 0.20, 0.35, 0.25)])
        );
        assert_eq!(
            parse_highlight("0 0 1 1 rect"),
            Ok(vec![rect(0.0, 0.0, 1.0, 1.0)])
        );
        assert_eq!(
            parse_highlight("0.7 0.1 0.3 0.9"),
            Ok(vec![rect(0.7, 0.1, 0.3, 0.9)]),
            "0.7 + 0.3 is 1, not more"
        );
    }

    #[test]
    fn several_areas_and_ellipses() {
        let areas =
            parse_highlight("0.1 0.1 0.2 0.2 ;0.5 0.5 0.4 0.3 ellipse;  0 0 .5 .5").expect("valid");
        assert_eq!(areas.len(), 3);
        assert_eq!(areas[0], rect(0.1, 0.1, 0.2, 0.2));
        assert_eq!(areas[1].shape, Shape::Ellipse);
        assert_eq!((areas[1].left, areas[1].height), (0.5, 0.3));
        assert_eq!(areas[2], rect(0.0, 0.0, 0.5, 0.5));
    }

    #[test]
    fn no_argument_clears() {
        assert_eq!(parse_highlight(""), Ok(Vec::new()));
        assert_eq!(parse_highlight("  "), Ok(Vec::new()));
    }

    #[test]
    fn each_problem_points_at_its_word() {
        assert_eq!(
            problems("0.1 0.2 0.3"),
            [(0, "Found 3 value(s) where a".to_owned())]
        );
        assert_eq!(
            problems("0.1 0.2 0.3 0.4 0.5"),
            [(0, "Found 5 value(s) where a".to_owned())]
        );
        assert_eq!(
            problems("0.1 abc 0.3 0.4"),
            [(4, "`abc` is not a number. H".to_owned())]
        );
        assert_eq!(
            problems("0.1 0.2 1.5 0.4"),
            [(8, "The width `1.5` must be ".to_owned())]
        );
        assert_eq!(
            problems("-0.1 0.2 0.3 0.4"),
            [(0, "The left `-0.1` must be ".to_owned())]
        );
        assert_eq!(
            problems("0.1 0.2 0 0.4"),
            [(8, "The width `0` must be a ".to_owned())]
        );
        assert_eq!(
            problems("0.8 0.2 0.3 0.4"),
            [(8, "The area reaches past th".to_owned())]
        );
        assert_eq!(
            problems("0.1 0.7 0.3 0.4"),
            [(12, "The area reaches past th".to_owned())]
        );
        assert_eq!(
            problems("0.1 0.2 0.3 0.4 circle"),
            [(16, "`circle` is not a shape.".to_owned())]
        );
    }

    #[test]
    fn problems_in_later_areas_and_empty_areas_are_located() {
        assert_eq!(
            problems("0.1 0.2 0.3 0.4; 0.5 0.5 0.6 0.1"),
            [(25, "The area reaches past th".to_owned())]
        );
        assert_eq!(
            problems("0.1 0.2 0.3 0.4;"),
            [(15, "There is no area between".to_owned())]
        );
        assert_eq!(
            problems("0.1 0.2 0.3 0.4 ;; 0 0 1 1"),
            [(17, "There is no area between".to_owned())]
        );
        let both = problems("1 2 3 4; x 0 1 1");
        assert_eq!(
            both.iter().map(|p| p.0).collect::<Vec<_>>(),
            [2, 9],
            "{both:?}"
        );
        let message = &parse_highlight("0.8 0 0.3 1").expect_err("too wide")[0].message;
        assert!(
            message.contains("left 0.8 plus width 0.3 is more than 1. Make the width at most 0.2."),
            "{message}"
        );
    }

    #[test]
    fn words_keep_their_byte_offsets() {
        assert_eq!(
            words_with_offsets(" 1  2.5\t3", 10),
            [(11, "1"), (14, "2.5"), (18, "3")]
        );
        assert!(words_with_offsets("   ", 0).is_empty());
    }
}
