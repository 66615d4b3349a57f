//! Who a request really comes from. The connection's peer address is a fact; an
//! `X-Forwarded-For` header is a claim anybody can write. Only the reverse proxies the site
//! lists (`server: trusted_proxies` in `docent.yaml`) are believed when they name a client;
//! from any other peer the header cannot move the client to another address (so guessing
//! cannot escape or misdirect the wait after wrong credentials), it can only make the client
//! count as remote (so a tunnel or proxy nobody listed never passes for this machine).

use std::net::{IpAddr, SocketAddr};

use crate::access::is_loopback;

/// The reverse proxies whose `X-Forwarded-For` is believed.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TrustedProxies(Vec<IpAddr>);

/// A client as far as Docent can tell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ClientAddress {
    /// The address its failed credentials count against, its kiosk allowance is kept under
    /// and that is logged: the connection's peer, or the client a trusted proxy names.
    /// `None` when unknown (a router called without connection info, in tests).
    pub ip: Option<IpAddr>,
    /// Whether the client is on this machine: its address is loopback and no proxy says it
    /// came from elsewhere. Only such a client gets what this machine gets (an `--open`
    /// server, an adapter without a credential).
    pub local: bool,
}

impl ClientAddress {
    /// A client known only by its connection's peer address.
    pub fn direct(ip: Option<IpAddr>) -> Self {
        ClientAddress {
            ip,
            local: is_loopback(ip),
        }
    }
}

impl TrustedProxies {
    /// These proxies (from `server: trusted_proxies`).
    pub fn new(proxies: Vec<IpAddr>) -> Self {
        TrustedProxies(proxies.into_iter().map(canonical).collect())
    }

    /// Whether `peer` is one of the listed proxies.
    pub fn contains(&self, peer: IpAddr) -> bool {
        self.0.contains(&canonical(peer))
    }

    /// The client behind a connection from `peer` that carried these `X-Forwarded-For`
    /// header values (in order; `None` for one that is not text).
    ///
    /// From a listed proxy, the entries are read from the right (each proxy appends the
    /// address it got the request from) past further listed proxies: the first other entry is
    /// the client. An entry that is not an address there leaves the client unknown: it is
    /// counted and logged under the proxy that passed it on, and is not local.
    pub fn client(&self, peer: Option<IpAddr>, forwarded: &[Option<&str>]) -> ClientAddress {
        let direct = ClientAddress::direct(peer);
        let entries = || {
            forwarded
                .iter()
                .rev()
                .flat_map(|value| match value {
                    Some(text) => text.rsplit(',').map(parse_entry).collect::<Vec<_>>(),
                    None => vec![None],
                })
                .filter(|entry| *entry != Some(Entry::Empty))
        };
        let Some(mut hop) = peer.filter(|p| self.contains(*p)) else {
            // Not a listed proxy: the header may only take away what loopback would give.
            let claims_elsewhere = entries().any(|e| match e {
                Some(Entry::Address(ip)) => !is_loopback(Some(ip)),
                _ => true,
            });
            return ClientAddress {
                local: direct.local && !claims_elsewhere,
                ..direct
            };
        };
        for entry in entries() {
            match entry {
                Some(Entry::Address(ip)) if self.contains(ip) => hop = ip,
                Some(Entry::Address(ip)) => return ClientAddress::direct(Some(ip)),
                _ => {
                    return ClientAddress {
                        ip: Some(hop),
                        local: false,
                    };
                }
            }
        }
        // Only proxies named (or no header at all): the nearest of them is asking itself.
        ClientAddress::direct(Some(hop))
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Entry {
    Address(IpAddr),
    Empty,
}

/// One `X-Forwarded-For` entry: an address, possibly with a port (`203.0.113.7:4711`,
/// `[2001:db8::1]:4711`); `None` when it is neither.
fn parse_entry(text: &str) -> Option<Entry> {
    let text = text.trim();
    if text.is_empty() {
        return Some(Entry::Empty);
    }
    let ip = (text.parse::<IpAddr>().ok())
        .or_else(|| text.parse::<SocketAddr>().ok().map(|s| s.ip()))?;
    Some(Entry::Address(canonical(ip)))
}

/// An IPv4 address that arrived mapped into IPv6 (`::ffff:10.0.0.2`, how a server listening
/// on `[::]` sees IPv4 peers) as the IPv4 address it is.
fn canonical(ip: IpAddr) -> IpAddr {
    match ip {
        IpAddr::V6(v6) => v6.to_ipv4_mapped().map_or(ip, IpAddr::V4),
        v4 => v4,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ip(text: &str) -> Option<IpAddr> {
        Some(text.parse().unwrap())
    }

    #[test]
    fn an_unlisted_peer_cannot_move_its_address_with_the_header() {
        let none = TrustedProxies::default();
        for header in ["203.0.113.9", "127.0.0.1", "garbage", "10.0.0.1, 127.0.0.1"] {
            let client = none.client(ip("127.0.0.2"), &[Some(header)]);
            assert_eq!(client.ip, ip("127.0.0.2"), "{header}");
        }
        // ... but a header naming another machine makes a loopback peer remote.
        assert!(!none.client(ip("127.0.0.1"), &[Some("203.0.113.9")]).local);
        assert!(!none.client(ip("127.0.0.1"), &[Some("garbage")]).local);
        assert!(!none.client(ip("127.0.0.1"), &[None]).local);
        assert!(none.client(ip("127.0.0.1"), &[Some("127.0.0.1")]).local);
        assert!(none.client(ip("127.0.0.1"), &[]).local);
        assert!(!none.client(ip("192.0.2.4"), &[Some("127.0.0.1")]).local);
    }

    #[test]
    fn a_listed_proxy_names_the_client_last_before_itself() {
        let proxies = TrustedProxies::new(vec![ip("10.0.0.2").unwrap(), ip("10.0.0.3").unwrap()]);
        let client = |header: &[Option<&str>]| proxies.client(ip("10.0.0.2"), header);
        // What the client wrote itself (left) is never believed over what the proxy appended.
        assert_eq!(client(&[Some("127.0.0.1, 192.0.2.7")]).ip, ip("192.0.2.7"));
        assert!(!client(&[Some("127.0.0.1, 192.0.2.7")]).local);
        // A chain of listed proxies is walked through; headers repeated are one list.
        assert_eq!(client(&[Some("192.0.2.7, 10.0.0.3")]).ip, ip("192.0.2.7"));
        assert_eq!(
            client(&[Some("192.0.2.7"), Some("10.0.0.3")]).ip,
            ip("192.0.2.7")
        );
        assert_eq!(client(&[Some("[2001:db8::7]:4711")]).ip, ip("2001:db8::7"));
        assert_eq!(client(&[Some("192.0.2.7:4711")]).ip, ip("192.0.2.7"));
        // Unreadable: counted under the proxy, never local.
        let unreadable = client(&[Some("192.0.2.7, nonsense")]);
        assert_eq!((unreadable.ip, unreadable.local), (ip("10.0.0.2"), false));
        // No header: the proxy itself.
        assert_eq!(client(&[]).ip, ip("10.0.0.2"));
        // A proxy on this machine forwarding a local client.
        let local = TrustedProxies::new(vec![ip("127.0.0.1").unwrap()]);
        let mapped = local.client(ip("::ffff:127.0.0.1"), &[Some("127.0.0.1")]);
        assert!(mapped.local);
        assert!(!local.client(ip("127.0.0.1"), &[Some("192.0.2.7")]).local);
    }
}
