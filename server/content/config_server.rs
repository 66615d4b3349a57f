//! `docent.yaml`'s `server:` limits in validated form: how many connections one address and
//! all clients may hold, how long a request may take to arrive, the largest websocket message
//! and how many frames may wait for one client. Read by `config_file/server.rs`; the runtime
//! builds its connection limits, websocket settings and outgoing queues from these at start-up,
//! so the defaults here are the only place the figures are written. Documented for people in
//! `docs/CONFIG.md` and `docs/PROTOCOL.md` (Limits and timeouts).

use std::ops::RangeInclusive;
use std::time::Duration;

/// The limits Docent's own server keeps (`server:` in `docent.yaml`), in force from start-up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ServerLimits {
    /// Open connections (websockets included) one client address may hold
    /// (`connections: per_address`); an IPv6 /64 counts as one address.
    pub per_address: usize,
    /// Open connections in all (`connections: total`).
    pub total: usize,
    /// A request's headers must arrive within this long (`timeouts: headers`); an idle
    /// keep-alive connection is closed after it too.
    pub header_timeout: Duration,
    /// A request's body must arrive within this long of its headers (`timeouts: body`).
    pub body_timeout: Duration,
    /// Bytes of the largest websocket message (`messages: max_size`); a larger one closes
    /// the connection with 1009.
    pub max_message_bytes: usize,
    /// Frames that may wait for one websocket client (`queues: per_client`).
    pub queue_per_client: usize,
}

impl ServerLimits {
    /// The connection caps a setting may ask for (`connections: per_address`, `total`). Each
    /// connection is a file descriptor; beyond tens of thousands a museum robot runs out of other
    /// things first.
    pub const CONNECTIONS: RangeInclusive<usize> = 1..=65_536;

    /// The time limits a setting may ask for (`timeouts: headers`, `body`): under a second no
    /// client on a busy network keeps up, over ten minutes a slow client holds its place too long.
    pub const TIMEOUTS: RangeInclusive<Duration> =
        Duration::from_secs(1)..=Duration::from_secs(600);

    /// The websocket message sizes a setting may ask for (`messages: max_size`), in bytes. Not
    /// below the protocol's frame limit (16 KiB, `docent-protocol`'s `MAX_FRAME_BYTES`): a frame the
    /// protocol answers with `frame-too-large` must reach it rather than end the connection. Not
    /// above 64 MiB: every connection may hold one such message in memory.
    pub const MESSAGE_SIZES: RangeInclusive<usize> = 16 * 1024..=64 * 1024 * 1024;

    /// The outgoing queue lengths a setting may ask for (`queues: per_client`), in frames. Not
    /// below 256: an operator joining is sent the last 200 events at once, after its `welcome`.
    pub const QUEUE_LENGTHS: RangeInclusive<usize> = 256..=65_536;
}

impl Default for ServerLimits {
    fn default() -> Self {
        ServerLimits {
            per_address: 128,
            total: 1024,
            header_timeout: Duration::from_secs(30),
            body_timeout: Duration::from_secs(30),
            max_message_bytes: 1024 * 1024,
            queue_per_client: 1024,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::ServerLimits;

    #[test]
    fn the_defaults_are_settings_a_file_could_write() {
        let limits = ServerLimits::default();
        assert!(ServerLimits::CONNECTIONS.contains(&limits.per_address));
        assert!(ServerLimits::CONNECTIONS.contains(&limits.total));
        assert!(limits.per_address <= limits.total);
        assert!(ServerLimits::TIMEOUTS.contains(&limits.header_timeout));
        assert!(ServerLimits::TIMEOUTS.contains(&limits.body_timeout));
        assert!(ServerLimits::MESSAGE_SIZES.contains(&limits.max_message_bytes));
        assert!(ServerLimits::QUEUE_LENGTHS.contains(&limits.queue_per_client));
    }
}
