//! Requests whose length is ambiguous: both `Content-Length` and `Transfer-Encoding`. A proxy
//! in front of Docent may read such a request's body by one and Docent by the other, which is
//! how requests are smuggled past a proxy. hyper itself reads the body as chunked and closes
//! the connection afterwards, but still hands the request on, with the `Content-Length`
//! removed; so [`Sniffed`] watches the header bytes as hyper reads them and notes which
//! request on the connection was ambiguous, and the connection's service refuses it (`400
//! conflicting-length`). (Two different `Content-Length` values hyper refuses itself.)
//!
//! Only header blocks are looked at; the bodies of requests with a `Content-Length` are
//! skipped. After a chunked body or an upgrade (websocket) the rest of the connection is not
//! watched: hyper reads no further request after an ambiguous one, and a chunked request
//! without `Content-Length` is not ambiguous.

use std::io;
use std::pin::Pin;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::task::{Context, Poll};

use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};

/// The longest header block watched; hyper refuses far shorter ones anyway.
const MAX_HEAD_BYTES: usize = 64 * 1024;

/// Which request on a connection (counted from 1) had both lengths; 0 when none did.
#[derive(Clone, Default)]
pub(super) struct Ambiguous(Arc<AtomicU64>);

impl Ambiguous {
    /// Whether request number `n` (from 1) of the connection was ambiguous.
    pub(super) fn is(&self, n: u64) -> bool {
        self.0.load(Ordering::Acquire) == n
    }
}

enum Watch {
    /// Reading the header block of request number `.1`, bytes so far in `.0`.
    Head(Vec<u8>, u64),
    /// Skipping this many body bytes before request number `.1`.
    Body(u64, u64),
    /// Not watching any more.
    Off,
}

/// A connection whose incoming header blocks are watched.
pub(super) struct Sniffed<T> {
    inner: T,
    watch: Watch,
    ambiguous: Ambiguous,
}

impl<T> Sniffed<T> {
    /// Watches `inner`, noting ambiguous requests in `ambiguous`.
    pub(super) fn new(inner: T, ambiguous: Ambiguous) -> Self {
        Sniffed {
            inner,
            watch: Watch::Head(Vec::new(), 1),
            ambiguous,
        }
    }

    fn feed(&mut self, mut bytes: &[u8]) {
        while !bytes.is_empty() {
            match &mut self.watch {
                Watch::Off => return,
                Watch::Body(left, next) => {
                    let skip = bytes
                        .len()
                        .min(usize::try_from(*left).unwrap_or(usize::MAX));
                    bytes = &bytes[skip..];
                    *left -= skip as u64;
                    if *left == 0 {
                        self.watch = Watch::Head(Vec::new(), *next);
                    }
                }
                Watch::Head(head, number) => {
                    let number = *number;
                    let searched = head.len().saturating_sub(3);
                    head.extend_from_slice(bytes);
                    let Some(end) = find_blank_line(&head[searched..]).map(|i| searched + i + 4)
                    else {
                        if head.len() > MAX_HEAD_BYTES {
                            self.watch = Watch::Off;
                        }
                        return;
                    };
                    let rest = head.split_off(end);
                    self.watch = match framing(head) {
                        Framing::Ambiguous => {
                            self.ambiguous.0.store(number, Ordering::Release);
                            Watch::Off
                        }
                        Framing::Length(0) => Watch::Head(Vec::new(), number + 1),
                        Framing::Length(n) => Watch::Body(n, number + 1),
                        Framing::Other => Watch::Off,
                    };
                    return self.feed(&rest);
                }
            }
        }
    }
}

fn find_blank_line(bytes: &[u8]) -> Option<usize> {
    bytes.windows(4).position(|w| w == b"\r\n\r\n")
}

enum Framing {
    Ambiguous,
    Length(u64),
    /// Chunked, an upgrade, or unreadable: stop watching.
    Other,
}

/// How the body after this header block is framed.
fn framing(head: &[u8]) -> Framing {
    let (mut length, mut chunked, mut upgrade) = (None, false, false);
    let lines = head.split(|b| *b == b'\n').skip(1);
    for line in lines {
        let Some(colon) = line.iter().position(|b| *b == b':') else {
            continue;
        };
        let name = line[..colon].trim_ascii();
        let value = line[colon + 1..].trim_ascii();
        if name.eq_ignore_ascii_case(b"content-length") {
            let parsed = std::str::from_utf8(value).ok().and_then(|v| v.parse().ok());
            length = Some(parsed);
        } else if name.eq_ignore_ascii_case(b"transfer-encoding") {
            chunked = true;
        } else if name.eq_ignore_ascii_case(b"upgrade") {
            upgrade = true;
        }
    }
    match (length, chunked) {
        (Some(_), true) => Framing::Ambiguous,
        (Some(Some(n)), false) if !upgrade => Framing::Length(n),
        (None, false) if !upgrade => Framing::Length(0),
        _ => Framing::Other,
    }
}

impl<T: AsyncRead + Unpin> AsyncRead for Sniffed<T> {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        let before = buf.filled().len();
        let polled = Pin::new(&mut self.inner).poll_read(cx, buf);
        if let Poll::Ready(Ok(())) = polled
            && !matches!(self.watch, Watch::Off)
        {
            self.feed(&buf.filled()[before..]);
        }
        polled
    }
}

impl<T: AsyncWrite + Unpin> AsyncWrite for Sniffed<T> {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        Pin::new(&mut self.inner).poll_write(cx, buf)
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.inner).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.inner).poll_shutdown(cx)
    }

    fn poll_write_vectored(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bufs: &[io::IoSlice<'_>],
    ) -> Poll<io::Result<usize>> {
        Pin::new(&mut self.inner).poll_write_vectored(cx, bufs)
    }

    fn is_write_vectored(&self) -> bool {
        self.inner.is_write_vectored()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn watched(chunks: &[&str]) -> Ambiguous {
        let ambiguous = Ambiguous::default();
        let mut sniffed = Sniffed::new((), ambiguous.clone());
        for chunk in chunks {
            sniffed.feed(chunk.as_bytes());
        }
        ambiguous
    }

    #[test]
    fn the_ambiguous_request_is_found_by_its_number_across_reads_and_bodies() {
        let plain = "GET / HTTP/1.1\r\nHost: x\r\n\r\n";
        let with_body = "POST /a HTTP/1.1\r\nContent-Length: 5\r\n\r\nab\r\n\r";
        let both = "POST /b HTTP/1.1\r\nContent-length: 3\r\nTransfer-Encoding: chunked\r\n\r\n";
        let found = watched(&[plain, with_body, &both[..20], &both[20..]]);
        assert!(found.is(3));
        assert!(!found.is(1) && !found.is(2));
        assert!(watched(&[plain, plain]).0.load(Ordering::Acquire) == 0);
        // After an upgrade nothing more is read as headers.
        let upgrade = "GET /ws HTTP/1.1\r\nUpgrade: websocket\r\n\r\n";
        assert!(watched(&[upgrade, both]).0.load(Ordering::Acquire) == 0);
    }
}
