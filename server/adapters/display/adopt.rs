//! A kiosk that reconnects says which page it shows (`hello.page`). A restarted server has
//! only its home page in its display state: it adopts the kiosk's page instead of sending the
//! visitor home. Only a `DISPLAY_PAGE` that came while no touchscreen was connected (the tour
//! moved on while the kiosk was away) wins over what the kiosk shows; the caller has checked
//! that the page is one of the bundle's.

use tokio::sync::broadcast;

use crate::adapters::display::{Display, DisplayState, display_changed};
use crate::events::ClientRole;
use crate::sync::lock;
use crate::wire::outbox::Frame;

impl DisplayState {
    /// [`join`](Self::join) for a kiosk that shows `page`: the state takes that page unless a
    /// command moved the touchscreen while none was connected. Returns whether it did.
    pub fn join_kiosk_showing(
        &self,
        client: u64,
        page: String,
    ) -> (Display, Option<broadcast::Receiver<Frame>>, bool) {
        let adopted = {
            let mut current = lock(&self.current);
            let adopt = !current.page_commanded_unseen;
            if adopt && current.display.page.as_deref() != Some(page.as_str()) {
                current.display.page = Some(page);
                self.hub.publish(display_changed(&current.display));
            }
            adopt
        };
        // A command in between is either in the state the kiosk gets or sent to it.
        let (display, rx) = self.join(ClientRole::Kiosk, client);
        (display, rx, adopted)
    }
}
