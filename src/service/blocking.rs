//! The one way a handler runs blocking work (reading and writing files, parsing and checking
//! what a request brought): on tokio's blocking pool, so no runtime thread waits on a disk
//! or a parser while other requests queue behind it.

use super::error::ApiError;

/// Runs `work` on the blocking pool and answers its error, or a panic in it, as the API does
/// (`From<E> for ApiError`), so a handler writes `blocking(move || ...).await?`.
pub(crate) async fn blocking<T, E>(
    work: impl FnOnce() -> Result<T, E> + Send + 'static,
) -> Result<T, ApiError>
where
    T: Send + 'static,
    E: Send + 'static,
    ApiError: From<E>,
{
    Ok(tokio::task::spawn_blocking(work).await??)
}
