//! What the corpus says about a dialog manager's proposals (`proposal.*`): made, and then
//! accepted or dismissed by an operator, or withdrawn when the dialog manager left.

use serde::{Deserialize, Serialize};

/// The fields of a `proposal.made` event ([`super::EventKind::ProposalMade`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct ProposalMade {
    /// The proposal's id.
    pub proposal: u64,
    /// The dialog manager's connection.
    pub client: u64,
    /// The act proposed.
    pub label: String,
    /// The context it would be triggered in (the current one when absent).
    pub context: Option<String>,
    /// Why, in the dialog manager's words.
    pub reason: Option<String>,
}

/// The fields of a `proposal.accepted` event ([`super::EventKind::ProposalAccepted`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct ProposalAccepted {
    /// The proposal's id.
    pub proposal: u64,
    /// The operator's connection.
    pub client: u64,
    /// The act.
    pub label: String,
    /// The trigger it became.
    pub trigger: u64,
}

/// The fields of a `proposal.dismissed` event ([`super::EventKind::ProposalDismissed`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct ProposalDismissed {
    /// The proposal's id.
    pub proposal: u64,
    /// The operator's connection.
    pub client: u64,
    /// The act.
    pub label: String,
}

/// The fields of a `proposal.withdrawn` event ([`super::EventKind::ProposalWithdrawn`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct ProposalWithdrawn {
    /// The proposal's id.
    pub proposal: u64,
    /// The dialog manager's connection.
    pub client: u64,
    /// The act.
    pub label: String,
    /// Why.
    pub reason: String,
}
