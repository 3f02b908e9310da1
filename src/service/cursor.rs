//! The cursor of a list's next page, signed so that the server knows it gave it, for this
//! list. A cursor is `<nanoseconds>-<id>-<mac>`: the last item's creation time and id, and an
//! HMAC-SHA-256 (RFC 2104) under the server's [`CursorKey`] of the list's path, its filter
//! parameters and that position, cut to 16 bytes. A cursor made up, edited, or taken from
//! another list or another filter (`?status=done` for `?status=queued`) fails the check, and
//! the list answers 400 rather than a page of some other walk.
//!
//! The key is drawn at each start and never stored. A restart thus ends the walks under way
//! (their next page is a 400 saying to start again from the first page), which a client
//! sees rarely and recovers from at once; a key kept in the data directory would instead be
//! a secret copied by every backup of it, for walks that outlive a restart. `limit` is not
//! signed: a client may change its page size mid-walk without losing its place.

use std::fmt::Write as _;

use hmac::{Hmac, Mac};
use sha2::Sha256;
use uuid::Uuid;

/// HMAC-SHA-256, from RustCrypto's `hmac` beside its `sha2`.
type HmacSha256 = Hmac<Sha256>;

/// Bytes of the MAC a cursor carries: 128 bits, beyond guessing by any number of requests.
const MAC_BYTES: usize = 16;

/// The server's secret for signing cursors: 32 random bytes drawn at start.
#[derive(Clone)]
pub(crate) struct CursorKey([u8; 32]);

impl CursorKey {
    /// A new random key: two version-4 UUIDs, 244 bits from the operating system's
    /// generator (`getrandom`, under `uuid`), which no client can predict.
    pub(crate) fn random() -> Self {
        let mut key = [0u8; 32];
        key[..16].copy_from_slice(Uuid::new_v4().as_bytes());
        key[16..].copy_from_slice(Uuid::new_v4().as_bytes());
        Self(key)
    }

    /// A key of fixed bytes, for tests that must sign and check alike.
    #[cfg(test)]
    pub(crate) fn fixed(byte: u8) -> Self {
        Self([byte; 32])
    }

    /// The HMAC-SHA-256 of `parts` under this key, ready to finish or verify; each part is
    /// preceded by its length, so no two different lists of parts sign the same bytes.
    fn mac(&self, parts: &[&str]) -> HmacSha256 {
        let mut mac = HmacSha256::new_from_slice(&self.0).expect("HMAC takes a key of any length");
        for part in parts {
            mac.update(&(part.len() as u64).to_be_bytes());
            mac.update(part.as_bytes());
        }
        mac
    }
}

/// Where a page starts: after the item created at `created_at_ns` with `id`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Cursor {
    /// The item's creation time, ns since the Unix epoch.
    pub(crate) created_at_ns: i128,
    /// The item's id.
    pub(crate) id: Uuid,
}

/// The list a cursor belongs to: its path and its filter parameters as the query gives them
/// (`name=value`, in the query's sorted order; not `limit` or `cursor`).
pub(crate) struct ListScope<'a> {
    /// The list's path, `/api/v1/jobs`.
    pub(crate) path: &'a str,
    /// Its filters, `status=done`.
    pub(crate) filters: Vec<String>,
}

impl ListScope<'_> {
    /// The MAC of `position` in this list under `key`.
    fn mac(&self, key: &CursorKey, position: &str) -> HmacSha256 {
        let mut parts = vec![self.path];
        parts.extend(self.filters.iter().map(String::as_str));
        parts.push(position);
        key.mac(&parts)
    }
}

impl Cursor {
    /// `<nanoseconds>-<id>`, the position a MAC covers.
    fn position(self) -> String {
        format!("{}-{}", self.created_at_ns, self.id.simple())
    }

    /// `<nanoseconds>-<id>-<mac>`: opaque to clients, which pass it back as given.
    pub(crate) fn encode(self, key: &CursorKey, scope: &ListScope<'_>) -> String {
        let position = self.position();
        let mut text = format!("{position}-");
        let tag = scope.mac(key, &position).finalize().into_bytes();
        for byte in &tag[..MAC_BYTES] {
            // Writing to a String cannot fail.
            let _ = write!(text, "{byte:02x}");
        }
        text
    }

    /// The cursor of `text` if this server gave it for this list under `key`, else `None`.
    pub(crate) fn decode(text: &str, key: &CursorKey, scope: &ListScope<'_>) -> Option<Self> {
        let (position, mac) = text.rsplit_once('-')?;
        let given = hex(mac)?;
        let (at, id) = position.rsplit_once('-')?;
        let cursor = Self {
            created_at_ns: at.parse().ok()?,
            id: Uuid::try_parse(id).ok()?,
        };
        // Compared in constant time: how many leading bytes match tells a client nothing.
        let verified = scope
            .mac(key, &cursor.position())
            .verify_truncated_left(&given);
        verified.is_ok().then_some(cursor)
    }
}

/// The [`MAC_BYTES`] bytes of a MAC written in lowercase hex, if `text` is one.
fn hex(text: &str) -> Option<[u8; MAC_BYTES]> {
    if text.len() != 2 * MAC_BYTES || !text.bytes().all(|b| matches!(b, b'0'..=b'9' | b'a'..=b'f'))
    {
        return None;
    }
    let mut bytes = [0u8; MAC_BYTES];
    for (i, byte) in bytes.iter_mut().enumerate() {
        *byte = u8::from_str_radix(&text[2 * i..2 * i + 2], 16).ok()?;
    }
    Some(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scope<'a>(path: &'a str, filters: &[&str]) -> ListScope<'a> {
        ListScope {
            path,
            filters: filters.iter().map(|f| (*f).to_owned()).collect(),
        }
    }

    #[test]
    fn a_cursor_reads_back_only_in_its_own_list_under_its_own_key() {
        let key = CursorKey::fixed(7);
        let cursor = Cursor {
            created_at_ns: 1_700_000_000_123_456_789,
            id: Uuid::from_u128(42),
        };
        let jobs = scope("/api/v1/jobs", &["status=done"]);
        let text = cursor.encode(&key, &jobs);
        assert_eq!(Cursor::decode(&text, &key, &jobs), Some(cursor));
        let queued = scope("/api/v1/jobs", &["status=queued"]);
        assert_eq!(Cursor::decode(&text, &key, &queued), None);
        let studies = scope("/api/v1/studies", &["status=done"]);
        assert_eq!(Cursor::decode(&text, &key, &studies), None);
        assert_eq!(Cursor::decode(&text, &CursorKey::fixed(8), &jobs), None);
        assert_eq!(Cursor::decode(&text, &CursorKey::random(), &jobs), None);
        // The old form, and a position moved under a MAC that does not cover it.
        assert_eq!(Cursor::decode(&cursor.position(), &key, &jobs), None);
        let mac = text
            .rsplit_once('-')
            .map(|(_, mac)| mac)
            .unwrap_or_default();
        let moved = format!("1-{}-{mac}", Uuid::from_u128(42).simple());
        assert_eq!(Cursor::decode(&moved, &key, &jobs), None);
    }

    /// RFC 4231's test case 2, under the key padded with zeros to 32 bytes as a
    /// [`CursorKey`] holds it: the padding leaves HMAC's value as it is.
    #[test]
    fn the_mac_is_hmac_sha_256() {
        let mut key = [0u8; 32];
        key[..4].copy_from_slice(b"Jefe");
        let mut mac = HmacSha256::new_from_slice(&key).expect("any length");
        mac.update(b"what do ya want for nothing?");
        let tag = mac.finalize().into_bytes();
        let text: String = tag.iter().map(|b| format!("{b:02x}")).collect();
        assert_eq!(
            text,
            "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843"
        );
    }
}
