//! What operators and dialog managers share beyond the dispatcher: the pending proposals of
//! mixed initiative ([`Proposals`]) and the visitor session the corpus marks belong to
//! ([`Visits`]). Both are small in-memory stores; every change is also an event, so the
//! corpus holds the full story.

mod proposals;
mod visits;

pub use proposals::{MAX_PENDING, Proposal, ProposalError, Proposals};
pub use visits::{Confirmation, ConsentRefused, VISITOR_GROUPS, Visits};
