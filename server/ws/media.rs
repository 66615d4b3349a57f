//! The media on its way to Chromium, told as it moves on: operators get every change
//! (`media` frame), kiosks the pages that show a file that just became ready (`changed`).

use crate::events::ClientRole;
use crate::media::{MediaState, MediaView};
use crate::state::AppState;

/// Tells operator consoles every change of the media on its way to Chromium (`media` frame),
/// and kiosks the pages that show a file that just became ready (`changed`: a kiosk showing
/// one reloads it, so a picture missing while it converted appears), until shutdown.
pub async fn tell_media(state: AppState) {
    let mut views = state.media.subscribe();
    let not_failed = |views: &[MediaView]| -> Vec<String> {
        (views.iter())
            .filter(|v| v.state != MediaState::Failed)
            .map(|v| v.file.clone())
            .collect()
    };
    let mut pending = not_failed(&views.borrow_and_update());
    loop {
        tokio::select! {
            () = state.life.shutdown.cancelled() => return,
            changed = views.changed() => {
                if changed.is_err() {
                    return;
                }
            }
        }
        let now = views.borrow_and_update().clone();
        state.send_to_role(
            ClientRole::Operator,
            &crate::ws::protocol::media_frame(&now),
        );
        let ready: Vec<String> = (pending.iter())
            .filter(|file| !now.iter().any(|v| &&v.file == file))
            .cloned()
            .collect();
        pending = not_failed(&now);
        let bundle = state.dispatcher.bundle();
        let mut pages: Vec<&str> = Vec::new();
        for conversion in bundle
            .conversions
            .iter()
            .filter(|c| ready.contains(&c.shown))
        {
            pages.extend(conversion.pages.iter().map(String::as_str));
        }
        pages.sort_unstable();
        pages.dedup();
        if !pages.is_empty() {
            let frame = crate::ws::protocol::changed_frame(&pages, false);
            state.send_to_role(ClientRole::Kiosk, &frame);
        }
    }
}
