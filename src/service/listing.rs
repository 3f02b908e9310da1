//! Lists that page: `GET /api/v1/jobs`, `/studies` and `/calibrations` answer at most
//! `?limit=N` items (default [`DEFAULT_LIMIT`], at most [`MAX_LIMIT`]), newest first (ties by
//! id), and the next page's URL in a `Link: <...>; rel="next"` header, as GitHub's API pages;
//! the body stays the JSON array it was. The next page starts after a cursor, the last
//! item's creation time and id, so items created meanwhile (newer, on the first page) shift
//! nothing; the cursor is signed for its list and filters (`cursor.rs`), so one the server
//! did not give for this list is a 400. A resource filters its list by query parameters, one
//! [`Filter`] each: adding a filter is one entry in the resource's list of filters.

use std::cmp::Reverse;
use std::collections::BTreeMap;
use std::fmt::Write;

use axum::Json;
use axum::extract::{FromRef, FromRequestParts, Query};
use axum::http::request::Parts;
use axum::http::{HeaderValue, header};
use axum::response::{IntoResponse, Response};
use serde::Serialize;
use time::OffsetDateTime;
use uuid::Uuid;

use super::cursor::{Cursor, CursorKey, ListScope};
use super::error::ApiError;

/// Items a page has when `?limit` is not given: a screenful, and about 30 KB of jobs.
pub(crate) const DEFAULT_LIMIT: usize = 100;

/// The most items one page may have: about 300 KB of jobs, a few milliseconds to answer.
pub(crate) const MAX_LIMIT: usize = 1000;

/// What a list is ordered by.
pub(crate) trait Listed {
    /// When the item was created; newer first.
    fn created_at(&self) -> OffsetDateTime;
    /// Its id; the order among items created at the same instant.
    fn id(&self) -> Uuid;
}

/// Whether an item passes one filter's test.
type Test<'a, T> = Box<dyn Fn(&T) -> bool + 'a>;

/// One query parameter that narrows a list.
pub(crate) enum Filter<T> {
    /// `?{name}=text`: items whose field contains the text, case-insensitively (compared
    /// in Unicode lowercase).
    Contains(&'static str, fn(&T) -> &str),
    /// `?{name}=text`: items one of whose fields contains the text, case-insensitively.
    AnyContains(&'static str, fn(&T) -> Vec<&str>),
    /// `?{name}=a,b`: items one of whose fields equals one of the values,
    /// case-insensitively.
    AnyEqual(&'static str, fn(&T) -> Vec<&str>),
    /// `?{name}=a,b`: items whose field is one of the values, each one of `allowed`.
    OneOf(
        &'static str,
        &'static [&'static str],
        fn(&T) -> &'static str,
    ),
}

impl<T> Filter<T> {
    fn name(&self) -> &'static str {
        match self {
            Self::Contains(name, _)
            | Self::AnyContains(name, _)
            | Self::AnyEqual(name, _)
            | Self::OneOf(name, ..) => name,
        }
    }

    /// The test of `wanted` (the parameter's value), or why the value is refused.
    fn test(&self, wanted: &str) -> Result<Test<'_, T>, ApiError> {
        match self {
            Self::Contains(_, field) => {
                let wanted = wanted.to_lowercase();
                Ok(Box::new(move |item| {
                    field(item).to_lowercase().contains(&wanted)
                }))
            }
            Self::AnyContains(_, fields) => {
                let wanted = wanted.to_lowercase();
                Ok(Box::new(move |item| {
                    fields(item)
                        .iter()
                        .any(|f| f.to_lowercase().contains(&wanted))
                }))
            }
            Self::AnyEqual(_, fields) => {
                let values: Vec<String> =
                    wanted.split(',').map(|v| v.trim().to_lowercase()).collect();
                Ok(Box::new(move |item| {
                    fields(item)
                        .iter()
                        .any(|f| values.contains(&f.to_lowercase()))
                }))
            }
            Self::OneOf(name, allowed, field) => {
                let values: Vec<&str> = wanted.split(',').map(str::trim).collect();
                if let Some(bad) = values.iter().find(|v| !allowed.contains(v)) {
                    return Err(ApiError::bad_request(format!(
                        "?{name}={bad:?}: expected one or more of {} (comma-separated)",
                        allowed.join(", ")
                    )));
                }
                let values: Vec<String> = values.into_iter().map(str::to_owned).collect();
                Ok(Box::new(move |item| {
                    values.iter().any(|v| v == field(item))
                }))
            }
        }
    }
}

/// The cursor of `item`, the last of a page.
fn cursor_of<T: Listed>(item: &T) -> Cursor {
    Cursor {
        created_at_ns: item.created_at().unix_timestamp_nanos(),
        id: item.id(),
    }
}

/// An item's place in the list's order, newest first, then by id: smaller comes first.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct Place {
    newest_first_ns: Reverse<i128>,
    id: Uuid,
}

impl Place {
    fn of<T: Listed>(item: &T) -> Self {
        Self {
            newest_first_ns: Reverse(item.created_at().unix_timestamp_nanos()),
            id: item.id(),
        }
    }

    /// Whether the item comes after `cursor`, the last item of the page before.
    fn after(self, cursor: Cursor) -> bool {
        let at = self.newest_first_ns.0;
        at < cursor.created_at_ns || (at == cursor.created_at_ns && self.id > cursor.id)
    }
}

/// The query of a list, as given (`limit`, `cursor` and the filters' parameters), and the
/// key its cursors are signed with.
pub(crate) struct ListQuery {
    params: BTreeMap<String, String>,
    key: CursorKey,
}

impl<S> FromRequestParts<S> for ListQuery
where
    S: Send + Sync,
    CursorKey: FromRef<S>,
{
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, ApiError> {
        let Query(params) =
            Query::<BTreeMap<String, String>>::from_request_parts(parts, state).await?;
        Ok(Self {
            params,
            key: CursorKey::from_ref(state),
        })
    }
}

/// One page of a list, and the URL of the next.
pub(crate) struct Page<T> {
    pub(crate) items: Vec<T>,
    pub(crate) next: Option<String>,
}

impl ListQuery {
    /// The page of `items` (in any order) this query asks for, at `path`, narrowed by the
    /// `filters` the query names; 400 for a parameter that is none of them, a limit out of
    /// [1, [`MAX_LIMIT`]] or a cursor that is not one this server gave.
    pub(crate) fn page<T: Listed>(
        &self,
        path: &str,
        items: Vec<T>,
        filters: &[Filter<T>],
    ) -> Result<Page<T>, ApiError> {
        self.page_shown(path, items, |item| item, filters)
    }

    /// The page of `handles` this query asks for, each shown as the `T` the list answers:
    /// the handles are ordered and cut at the cursor, and only those the page reaches are
    /// shown and filtered. A page of 50 from a store of 5000 jobs therefore clones 51
    /// records, not 5000: the clones were 5 ms of CPU a request (scripts/load_test.py,
    /// item 9).
    pub(crate) fn page_shown<K: Listed, T: Listed>(
        &self,
        path: &str,
        handles: Vec<K>,
        show: impl Fn(K) -> T,
        filters: &[Filter<T>],
    ) -> Result<Page<T>, ApiError> {
        let tests = self.tests(filters)?;
        let limit = self.limit()?;
        let scope = self.scope(path);
        let start = self.cursor(&scope)?;
        // Each handle's place is computed once: comparing `OffsetDateTime`s in the sort
        // was most of a page's cost (1.4 of 1.8 ms for a store of 5000 jobs).
        let mut placed: Vec<(Place, K)> = handles
            .into_iter()
            .map(|handle| (Place::of(&handle), handle))
            .filter(|(place, _)| start.is_none_or(|cursor| place.after(cursor)))
            .collect();
        placed.sort_unstable_by_key(|(place, _)| *place);
        let mut items: Vec<T> = placed
            .into_iter()
            .map(|(_, handle)| show(handle))
            .filter(|item| tests.iter().all(|t| t(item)))
            .take(limit + 1)
            .collect();
        let next = (items.len() > limit).then(|| {
            let cursor = cursor_of(&items[limit - 1]).encode(&self.key, &scope);
            self.next_url(path, &cursor)
        });
        items.truncate(limit);
        Ok(Page { items, next })
    }

    /// The tests of the filters the query names; 400 for a parameter that is none of them.
    fn tests<'f, T>(&self, filters: &'f [Filter<T>]) -> Result<Vec<Test<'f, T>>, ApiError> {
        let mut tests = Vec::new();
        for (name, value) in &self.params {
            match filters.iter().find(|f| f.name() == name) {
                Some(filter) => tests.push(filter.test(value)?),
                None if name == "limit" || name == "cursor" => {}
                None => {
                    let known: Vec<&str> = ["limit", "cursor"]
                        .into_iter()
                        .chain(filters.iter().map(Filter::name))
                        .collect();
                    return Err(ApiError::bad_request(format!(
                        "unknown query parameter {name:?}; this list takes {}",
                        known.join(", ")
                    )));
                }
            }
        }
        Ok(tests)
    }

    /// The list a cursor of this query belongs to: `path` and every parameter but `limit`
    /// and `cursor` (a page size may change mid-walk; the filters may not).
    fn scope<'a>(&self, path: &'a str) -> ListScope<'a> {
        ListScope {
            path,
            filters: self
                .params
                .iter()
                .filter(|(name, _)| !matches!(name.as_str(), "limit" | "cursor"))
                .map(|(name, value)| format!("{name}={value}"))
                .collect(),
        }
    }

    fn limit(&self) -> Result<usize, ApiError> {
        let Some(text) = self.params.get("limit") else {
            return Ok(DEFAULT_LIMIT);
        };
        match text.parse::<usize>() {
            Ok(limit) if (1..=MAX_LIMIT).contains(&limit) => Ok(limit),
            _ => Err(ApiError::bad_request(format!(
                "?limit={text:?}: expected a whole number from 1 to {MAX_LIMIT}"
            ))),
        }
    }

    /// The cursor the query gives, if the server gave it for this list (its path and
    /// filters) since it started; a 400 otherwise.
    fn cursor(&self, scope: &ListScope<'_>) -> Result<Option<Cursor>, ApiError> {
        self.params
            .get("cursor")
            .map(|text| {
                Cursor::decode(text, &self.key, scope).ok_or_else(|| {
                    ApiError::bad_request(format!(
                        "?cursor={:?} is not a cursor this server gave for this list and \
                         these filters (take it from the previous page's Link header; after \
                         a restart of the server, start again from the first page)",
                        super::extract::cut(text)
                    ))
                })
            })
            .transpose()
    }

    /// The URL of the page after `cursor`: this query with the cursor replaced.
    fn next_url(&self, path: &str, cursor: &str) -> String {
        let mut url = path.to_owned();
        let mut separator = '?';
        let params = self
            .params
            .iter()
            .filter(|(name, _)| name.as_str() != "cursor")
            .map(|(name, value)| (name.as_str(), value.as_str()))
            .chain([("cursor", cursor)]);
        for (name, value) in params {
            url.push(separator);
            separator = '&';
            encode_into(&mut url, name);
            url.push('=');
            encode_into(&mut url, value);
        }
        url
    }
}

/// Percent-encodes `text` into `url`, keeping RFC 3986's unreserved characters.
fn encode_into(url: &mut String, text: &str) {
    for byte in text.bytes() {
        if byte.is_ascii_alphanumeric() || b"-._~".contains(&byte) {
            url.push(char::from(byte));
        } else {
            // Writing to a String cannot fail.
            let _ = write!(url, "%{byte:02X}");
        }
    }
}

impl<T: Serialize> IntoResponse for Page<T> {
    fn into_response(self) -> Response {
        let mut response = Json(self.items).into_response();
        if let Some(next) = self.next {
            if let Ok(value) = HeaderValue::from_str(&format!("<{next}>; rel=\"next\"")) {
                response.headers_mut().insert(header::LINK, value);
            }
        }
        response
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Item {
        at: i64,
        id: u128,
        name: &'static str,
        status: &'static str,
    }

    impl Listed for Item {
        fn created_at(&self) -> OffsetDateTime {
            OffsetDateTime::from_unix_timestamp(self.at).unwrap_or(OffsetDateTime::UNIX_EPOCH)
        }
        fn id(&self) -> Uuid {
            Uuid::from_u128(self.id)
        }
    }

    const FILTERS: &[Filter<Item>] = &[
        Filter::OneOf("status", &["queued", "done"], |i| i.status),
        Filter::Contains("name", |i| i.name),
    ];

    fn items() -> Vec<Item> {
        (0..10u8)
            .map(|i| Item {
                at: 100 + i64::from(i / 2),
                id: u128::from(i),
                name: if i % 3 == 0 { "Load Ä" } else { "speed" },
                status: if i % 2 == 0 { "queued" } else { "done" },
            })
            .collect()
    }

    fn query(pairs: &[(&str, &str)]) -> ListQuery {
        ListQuery {
            params: pairs
                .iter()
                .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
                .collect(),
            key: CursorKey::fixed(1),
        }
    }

    /// The cursor a next URL carries, decoded from its percent-encoding.
    fn cursor_of(next: &str) -> String {
        let raw = next.split("cursor=").nth(1).unwrap_or_default();
        raw.split('&').next().unwrap_or_default().to_owned()
    }

    #[test]
    fn pages_follow_one_another_newest_first_without_gaps_or_repeats() {
        let mut seen = Vec::new();
        let mut cursor: Option<String> = None;
        loop {
            let mut pairs = vec![("limit", "3")];
            if let Some(c) = &cursor {
                pairs.push(("cursor", c.as_str()));
            }
            let page = query(&pairs)
                .page("/x", items(), FILTERS)
                .unwrap_or_else(|e| panic!("{}", e.status()));
            seen.extend(page.items.iter().map(|i| i.id));
            match page.next {
                Some(next) => cursor = Some(cursor_of(&next)),
                None => break,
            }
        }
        // Newest first: items 8 and 9 were created last; ties by id.
        assert_eq!(seen, vec![8, 9, 6, 7, 4, 5, 2, 3, 0, 1]);
    }

    #[test]
    fn an_item_created_between_pages_shifts_nothing() {
        let first = query(&[("limit", "4")]).page("/x", items(), FILTERS);
        let next = first.ok().and_then(|p| p.next).unwrap_or_default();
        let mut more = items();
        more.push(Item {
            at: 1000,
            id: 99,
            name: "new",
            status: "queued",
        });
        let cursor = cursor_of(&next);
        let second = query(&[("limit", "4"), ("cursor", &cursor)]).page("/x", more, FILTERS);
        let ids: Vec<u128> = second
            .map(|p| p.items.iter().map(|i| i.id).collect())
            .unwrap_or_default();
        assert_eq!(ids, vec![4, 5, 2, 3]);
    }

    #[test]
    fn filters_narrow_and_the_next_url_keeps_them() {
        let page = query(&[("status", "queued"), ("name", "load ä"), ("limit", "1")])
            .page("/api/v1/jobs", items(), FILTERS)
            .ok();
        let page = page.unwrap_or(Page {
            items: Vec::new(),
            next: None,
        });
        assert_eq!(page.items.iter().map(|i| i.id).collect::<Vec<_>>(), vec![6]);
        let next = page.next.unwrap_or_default();
        assert!(
            next.starts_with("/api/v1/jobs?limit=1&name=load%20%C3%A4&status=queued&cursor="),
            "{next}"
        );
        for bad in [
            vec![("status", "nope")],
            vec![("limit", "0")],
            vec![("limit", "1001")],
            vec![("cursor", "garbage")],
            vec![("colour", "red")],
        ] {
            let refused = query(&bad).page("/x", items(), FILTERS);
            assert_eq!(
                refused.err().map(|e| e.status().as_u16()),
                Some(400),
                "{bad:?}"
            );
        }
    }

    /// The status of the page `pairs` asks for at `path`: 200 or the refusal's.
    fn status(path: &str, pairs: &[(&str, &str)]) -> u16 {
        query(pairs)
            .page(path, items(), FILTERS)
            .map_or_else(|e| e.status().as_u16(), |_| 200)
    }

    /// Forged but well-formed cursors, and cursors from another list or filter, were paged
    /// from; the docs say a cursor the server did not give is a 400, and now it is.
    #[test]
    fn a_cursor_not_given_for_this_list_and_these_filters_is_a_400() {
        let first = query(&[("status", "done"), ("limit", "1")]).page("/x", items(), FILTERS);
        let next = first.ok().and_then(|p| p.next).unwrap_or_default();
        let cursor = cursor_of(&next);
        let genuine = [
            ("status", "done"),
            ("limit", "2"),
            ("cursor", cursor.as_str()),
        ];
        assert_eq!(status("/x", &genuine), 200, "{next}");
        let other_filter = [("status", "queued"), ("cursor", cursor.as_str())];
        assert_eq!(status("/x", &other_filter), 400);
        assert_eq!(status("/x", &[("cursor", cursor.as_str())]), 400);
        assert_eq!(
            status("/y", &[("status", "done"), ("cursor", cursor.as_str())]),
            400
        );
        // The position of a real item under a made-up MAC, and the old unsigned form.
        let forged = format!(
            "109000000000-{}-{}",
            Uuid::from_u128(9).simple(),
            "0".repeat(32)
        );
        assert_eq!(
            status("/x", &[("status", "done"), ("cursor", forged.as_str())]),
            400
        );
        let unsigned = format!("109000000000-{}", Uuid::from_u128(9).simple());
        assert_eq!(
            status("/x", &[("status", "done"), ("cursor", unsigned.as_str())]),
            400
        );
    }
}
