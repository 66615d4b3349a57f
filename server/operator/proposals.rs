//! Mixed initiative: a dialog manager proposes an act, an operator accepts (the act is
//! triggered) or dismisses it. This is the path for handing work from the operator to an
//! autonomous system step by step; the corpus records both outcomes.

use std::collections::BTreeMap;
use std::sync::Mutex;

use serde::Serialize;

use crate::sync::lock;
use crate::wire::ErrorCode;

/// Proposals that may wait at once; a dialog manager proposing faster than operators decide
/// is told so instead of burying the console.
pub const MAX_PENDING: usize = 50;

/// One proposal waiting for an operator.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Proposal {
    /// Its id, from 1 within one server run.
    pub proposal: u64,
    /// The proposing dialog manager's connection.
    pub client: u64,
    /// The act proposed.
    pub label: String,
    /// The context asked for (the current one when absent).
    pub context: Option<String>,
    /// Why, in the dialog manager's words.
    pub reason: Option<String>,
}

/// Why a proposal could not be made or settled.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum ProposalError {
    /// Too many are waiting already.
    #[error("{MAX_PENDING} proposals are already waiting for the operator; wait for answers")]
    TooMany,
    /// No such proposal is pending (it was settled by someone else, or never existed).
    #[error("proposal {0} is not pending (already accepted or dismissed?)")]
    NotPending(u64),
}

impl ProposalError {
    /// The error code on the wire.
    pub fn code(&self) -> ErrorCode {
        match self {
            ProposalError::TooMany => ErrorCode::TooManyProposals,
            ProposalError::NotPending(_) => ErrorCode::UnknownProposal,
        }
    }
}

/// The pending proposals.
#[derive(Debug, Default)]
pub struct Proposals {
    inner: Mutex<Inner>,
}

#[derive(Debug, Default)]
struct Inner {
    next: u64,
    pending: BTreeMap<u64, Proposal>,
}

impl Proposals {
    /// Records a proposal and returns it with its id. `announce` runs before anyone else can
    /// see it (under the lock), so its event always comes before any answer to it.
    pub fn propose(
        &self,
        client: u64,
        label: String,
        context: Option<String>,
        reason: Option<String>,
        announce: impl FnOnce(&Proposal),
    ) -> Result<Proposal, ProposalError> {
        let mut inner = lock(&self.inner);
        if inner.pending.len() >= MAX_PENDING {
            return Err(ProposalError::TooMany);
        }
        inner.next += 1;
        let proposal = Proposal {
            proposal: inner.next,
            client,
            label,
            context,
            reason,
        };
        announce(&proposal);
        inner.pending.insert(proposal.proposal, proposal.clone());
        Ok(proposal)
    }

    /// Takes out every pending proposal of `client` (a dialog manager that left: its
    /// proposals no longer stand for anything).
    pub fn withdraw_from(&self, client: u64) -> Vec<Proposal> {
        let mut inner = lock(&self.inner);
        let gone: Vec<u64> = (inner.pending.values())
            .filter(|p| p.client == client)
            .map(|p| p.proposal)
            .collect();
        gone.iter()
            .filter_map(|id| inner.pending.remove(id))
            .collect()
    }

    /// Takes a pending proposal out (to accept or dismiss it); only one operator can.
    pub fn settle(&self, id: u64) -> Result<Proposal, ProposalError> {
        lock(&self.inner)
            .pending
            .remove(&id)
            .ok_or(ProposalError::NotPending(id))
    }

    /// Puts a proposal back (its act could not be triggered after all).
    pub fn restore(&self, proposal: Proposal) {
        lock(&self.inner)
            .pending
            .insert(proposal.proposal, proposal);
    }

    /// The pending proposals, oldest first.
    pub fn pending(&self) -> Vec<Proposal> {
        lock(&self.inner).pending.values().cloned().collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_proposal_is_settled_once() {
        let proposals = Proposals::default();
        let made = proposals.propose(
            3,
            "WELCOME".into(),
            None,
            Some("a visitor came".into()),
            |_| {},
        );
        let made = made.expect("room");
        assert_eq!(made.proposal, 1);
        assert_eq!(proposals.pending(), std::slice::from_ref(&made));
        assert_eq!(proposals.settle(1), Ok(made));
        assert_eq!(proposals.settle(1), Err(ProposalError::NotPending(1)));
        assert!(proposals.pending().is_empty());
    }

    #[test]
    fn too_many_pending_proposals_are_refused() {
        let proposals = Proposals::default();
        for _ in 0..MAX_PENDING {
            proposals
                .propose(1, "A".into(), None, None, |_| {})
                .expect("room");
        }
        assert_eq!(
            proposals.propose(1, "A".into(), None, None, |_| {}),
            Err(ProposalError::TooMany)
        );
        proposals.settle(1).expect("pending");
        assert!(proposals.propose(1, "A".into(), None, None, |_| {}).is_ok());
    }

    #[test]
    fn a_leaving_dialog_managers_proposals_are_withdrawn() {
        let proposals = Proposals::default();
        for client in [1, 2, 1] {
            proposals
                .propose(client, "A".into(), None, None, |_| {})
                .expect("room");
        }
        let withdrawn: Vec<u64> = proposals
            .withdraw_from(1)
            .iter()
            .map(|p| p.proposal)
            .collect();
        assert_eq!(withdrawn, [1, 3]);
        assert_eq!(proposals.pending().len(), 1);
    }
}
