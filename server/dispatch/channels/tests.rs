//! The lane's decisions, one rule at a time (no dispatcher, no adapters).

use std::sync::Arc;

use super::*;
use crate::content::Args;
use crate::events::ActRef;

fn say(id: u64, trigger: u64, source: Source, priority: u8) -> Waiting {
    let act = ActRef {
        trigger,
        source,
        client: None,
        reference: None,
        label: format!("ACT{trigger}").into(),
        at: "acts.yaml:1".into(),
    };
    let command = Command {
        id,
        act: Arc::new(act),
        verb: Verb::Say,
        arg: Some("Hello".into()),
        args: Arc::new(Args::Say {
            text: "Hello".into(),
            language: None,
        }),
    };
    Waiting {
        command,
        waiter: None,
        priority,
    }
}

fn ids(d: &Decision) -> (Option<u64>, bool, Vec<u64>) {
    (
        d.run.as_ref().map(|w| w.command.id),
        d.cancel_running.is_some(),
        d.dropped.iter().map(|(w, _)| w.command.id).collect(),
    )
}

#[test]
fn a_queue_is_bounded_and_refuses_what_does_not_fit() {
    let mut lane = Lane::default();
    let policy = ChannelPolicy::queue(2);
    let ch = Channel::Speech;
    assert_eq!(
        ids(&lane.admit(say(1, 1, Source::Kiosk, 1), &ch, policy)).0,
        Some(1)
    );
    for n in 2..=3 {
        let d = lane.admit(say(n, n, Source::Kiosk, 1), &ch, policy);
        assert_eq!(ids(&d), (None, false, vec![]));
    }
    let d = lane.admit(say(4, 4, Source::Kiosk, 1), &ch, policy);
    assert_eq!(ids(&d), (None, false, vec![4]));
    assert!(
        d.dropped[0].1.contains("queue was full (2 waiting)"),
        "{}",
        d.dropped[0].1
    );
    assert_eq!(lane.waiting(), 2);
    assert_eq!(lane.finished(1).map(|w| w.command.id), Some(2));
    assert_eq!(lane.finished(2).map(|w| w.command.id), Some(3));
    assert!(lane.finished(3).is_none());
    assert!(lane.running().is_none());
}

#[test]
fn a_lower_priority_never_interrupts_a_higher_one() {
    for policy in [ChannelPolicy::replace(), ChannelPolicy::queue(1)] {
        let mut lane = Lane::default();
        let ch = Channel::Speech;
        lane.admit(say(1, 1, Source::Operator, 3), &ch, policy);
        let d = lane.admit(say(2, 2, Source::Kiosk, 1), &ch, policy);
        assert!(d.cancel_running.is_none(), "{policy:?}");
        assert_eq!(lane.running().map(|c| c.id), Some(1));
    }
}

#[test]
fn a_higher_priority_takes_over_and_clears_lower_waiting_work() {
    let mut lane = Lane::default();
    let (ch, policy) = (Channel::Speech, ChannelPolicy::queue(2));
    lane.admit(say(1, 1, Source::Kiosk, 1), &ch, policy);
    lane.admit(say(2, 2, Source::Kiosk, 1), &ch, policy);
    let d = lane.admit(say(3, 3, Source::Operator, 3), &ch, policy);
    assert_eq!(ids(&d), (Some(3), true, vec![2]));
    assert!(d.dropped[0].1.contains("the operator took over the speech"));
    // The cancelled command's end changes nothing: the operator's already runs.
    assert!(lane.finished(1).is_none());
    assert_eq!(lane.running().map(|c| c.id), Some(3));
}

#[test]
fn replace_cancels_equal_priority_work_and_drop_refuses_the_newcomer() {
    let ch = Channel::Projector;
    let mut lane = Lane::default();
    lane.admit(say(1, 1, Source::Dm, 2), &ch, ChannelPolicy::replace());
    let d = lane.admit(say(2, 2, Source::Dm, 2), &ch, ChannelPolicy::replace());
    assert_eq!(ids(&d), (Some(2), true, vec![]));
    assert!(lane.finished(1).is_none());
    assert_eq!(lane.running().map(|c| c.id), Some(2));
    let drop = ChannelPolicy {
        when_busy: WhenBusy::Drop,
        queue_limit: 2,
    };
    let d = lane.admit(say(3, 3, Source::Dm, 2), &ch, drop);
    assert_eq!(ids(&d), (None, false, vec![3]));
    assert!(
        d.dropped[0].1.contains("busy with SAY Hello"),
        "{}",
        d.dropped[0].1
    );
}

#[test]
fn an_acts_own_commands_wait_for_each_other_whatever_the_policy() {
    let mut lane = Lane::default();
    let ch = Channel::Drive;
    lane.admit(say(1, 7, Source::Kiosk, 1), &ch, ChannelPolicy::replace());
    let d = lane.admit(say(2, 7, Source::Kiosk, 1), &ch, ChannelPolicy::replace());
    assert_eq!(ids(&d), (None, false, vec![]));
    assert_eq!(lane.finished(1).map(|w| w.command.id), Some(2));
}

#[test]
fn cancelling_what_runs_starts_the_next_left_at_once() {
    let mut lane = Lane::default();
    let (ch, policy) = (Channel::Speech, ChannelPolicy::queue(2));
    lane.admit(say(1, 7, Source::Kiosk, 1), &ch, policy);
    lane.admit(say(2, 7, Source::Kiosk, 1), &ch, policy);
    lane.admit(say(3, 8, Source::Kiosk, 1), &ch, policy);
    let d = lane.cancel_where(|c, _| c.act.trigger == 7, "stopped");
    assert_eq!(ids(&d), (Some(3), true, vec![2]));
    assert!(lane.finished(1).is_none());
    assert_eq!(lane.running().map(|c| c.id), Some(3));
    let d = lane.cancel_where(|_, _| true, "stopped");
    assert_eq!(ids(&d), (None, true, vec![]));
    assert!(lane.running().is_none());
}

#[test]
fn a_full_queue_gives_way_to_a_higher_priority() {
    let mut lane = Lane::default();
    let (ch, policy) = (Channel::Speech, ChannelPolicy::queue(1));
    lane.admit(say(1, 1, Source::Operator, 3), &ch, policy);
    lane.admit(say(2, 2, Source::Kiosk, 1), &ch, policy);
    let d = lane.admit(say(3, 3, Source::Dm, 2), &ch, policy);
    assert_eq!(ids(&d), (None, false, vec![2]));
    assert_eq!(lane.finished(1).map(|w| w.command.id), Some(3));
}
