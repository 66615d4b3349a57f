//! The `log` adapter: carries nothing out, but keeps speech's pacing honest. A `SAY` is done
//! after the time the text would take to speak at the configured rate; any other verb routed
//! here (a site verb with `adapter: log`) is done at once. Every command is in the corpus.

use crate::adapters::worker::{Task, Worker};
use crate::adapters::{Command, Outcome};
use crate::content::{Verb, speaking_time};
use crate::lifecycle::Lifecycle;

/// The `log` adapter: speech (and site verbs) without a device, speaking at `rate_wpm` words
/// per minute.
pub fn log_adapter(rate_wpm: u32, life: &Lifecycle) -> Worker {
    Worker::start("log", Pacing { rate_wpm }, life)
}

struct Pacing {
    rate_wpm: u32,
}

impl Task for Pacing {
    async fn run(&self, command: &Command) -> Outcome {
        if command.verb == Verb::Say {
            let text = command.arg.as_deref().unwrap_or_default();
            tokio::time::sleep(speaking_time(text, self.rate_wpm)).await;
        }
        Outcome::Done
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn speaking_time_grows_with_words_and_falls_with_rate() {
        let short = speaking_time("Hello", 160);
        let long = speaking_time("Hello there, welcome to the museum of old computers", 160);
        assert!(long > short * 4);
        assert!(speaking_time("one two three", 600) < speaking_time("one two three", 100));
        assert_eq!(speaking_time("a b c d", 240), Duration::from_secs_f64(1.1));
    }
}
