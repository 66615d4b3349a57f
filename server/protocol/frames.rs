//! The server→client frames adapters send: `command` (to a screen or an external adapter
//! process) and `cancel`. Part of the websocket protocol, a compatibility boundary documented
//! in `docs/PROTOCOL.md`; the other frames are built in the runtime's `ws::protocol`.

use serde::Serialize;

use docent_content::Args;

#[derive(Serialize)]
#[serde(tag = "type", rename_all = "lowercase")]
enum AdapterFrame<'a> {
    Command {
        id: u64,
        trigger: u64,
        #[serde(rename = "ref")]
        reference: Option<&'a str>,
        label: &'a str,
        verb: &'a str,
        arg: Option<&'a str>,
        args: &'a Args,
        #[serde(skip_serializing_if = "Option::is_none")]
        speaking_ms: Option<u64>,
    },
    Cancel {
        verbs: Option<&'a [String]>,
        reason: &'a str,
    },
}

fn encode(frame: &AdapterFrame<'_>) -> String {
    // Plain data with string keys: serialization cannot fail.
    serde_json::to_string(frame).unwrap_or_default()
}

/// What a `command` frame says of one command.
#[derive(Clone, Copy, Debug)]
pub struct CommandFrame<'a> {
    /// The command's id, which its reports name.
    pub id: u64,
    /// The trigger that resolved its act.
    pub trigger: u64,
    /// The trigger's `ref`, as its sender gave it.
    pub reference: Option<&'a str>,
    /// The act's label.
    pub label: &'a str,
    /// The verb (`SAY`, `PROJECT`, a site's own).
    pub verb: &'a str,
    /// The argument as written.
    pub arg: Option<&'a str>,
    /// The argument, parsed.
    pub args: &'a Args,
    /// For a `SAY` to an adapter process or browser speech: how long saying it takes at the
    /// site's rate, in milliseconds (what a screen that only shows the text waits).
    pub speaking_ms: Option<u64>,
}

/// `command`: a command for an adapter or a display client.
pub fn command_frame(c: &CommandFrame<'_>) -> String {
    encode(&AdapterFrame::Command {
        id: c.id,
        trigger: c.trigger,
        reference: c.reference,
        label: c.label,
        verb: c.verb,
        arg: c.arg,
        args: c.args,
        speaking_ms: c.speaking_ms,
    })
}

/// `cancel`: drop queued commands and stop the current one (of `verbs`, or all).
pub fn cancel_frame(verbs: Option<&[String]>, reason: &str) -> String {
    encode(&AdapterFrame::Cancel { verbs, reason })
}

#[cfg(test)]
mod tests {
    use super::cancel_frame;

    #[test]
    fn cancel_frames_keep_their_bytes() {
        assert_eq!(
            cancel_frame(None, "stopped"),
            r#"{"type":"cancel","verbs":null,"reason":"stopped"}"#
        );
        let verbs = ["SAY".to_owned()];
        assert_eq!(
            cancel_frame(Some(&verbs), "interrupted"),
            r#"{"type":"cancel","verbs":["SAY"],"reason":"interrupted"}"#
        );
    }
}
