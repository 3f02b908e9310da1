# tribosim serve in a container.
#
#   docker build -t tribosim .
#   docker run -d -p 8080:8080 -v tribosim-data:/data -e TRIBOSIM_TOKEN=<secret> tribosim
#
# The server listens on 0.0.0.0 inside the container, which is not loopback, so it refuses
# to start without a token: pass TRIBOSIM_TOKEN (or append `--token ...` to the command).
# Or mount a file and pass `--token-file /run/secrets/tribosim-token` (docker secrets).
# Clients then send `Authorization: Bearer <secret>` on every /api/v1 call; /, /healthz and
# /api/v1/openapi.yaml stay open. Jobs and results live in the /data volume; on
# `docker stop` (SIGTERM) running jobs are interrupted and run again at the next start, and
# requests under way get 5 s (--shutdown-grace-s), within the 10 s docker waits.

# Base images are pinned by digest, so a rebuild uses the same toolchain and libraries. The
# digests are those published for the tags rust:1.95-slim-bookworm and debian:bookworm-slim;
# to move to newer ones: `docker buildx imagetools inspect <tag>` and replace them here.
FROM rust:1.95-slim-bookworm@sha256:d7482085ff5b415f84dba5647ae71606650bdef00db7aeb69f4b3d170c3e4082 AS build
WORKDIR /src
# Stripped and without debug info: a smaller image (profiling is done on a native build).
ENV CARGO_PROFILE_RELEASE_STRIP=symbols CARGO_PROFILE_RELEASE_DEBUG=0
COPY Cargo.toml Cargo.lock ./
# The dependencies alone, built against empty sources: this layer is reused until
# Cargo.toml or Cargo.lock change, so a source change recompiles only tribosim.
RUN mkdir src && echo 'fn main() {}' > src/main.rs && touch src/lib.rs \
    && cargo build --release --locked --bin tribosim \
    && rm -rf src
COPY build.rs ./
COPY src ./src
# The commit the results' provenance names (the repository is not in the image's context):
# docker build --build-arg TRIBOSIM_GIT_COMMIT=$(git rev-parse HEAD) .; "unknown" otherwise.
ARG TRIBOSIM_GIT_COMMIT=unknown
# Compiled into the binary (served at /api/v1/openapi.yaml and /): the runtime image needs
# no copy of either.
COPY openapi.yaml ./
COPY static ./static
# The sources are older than the dummy build's outputs: touch them so cargo rebuilds.
RUN touch src/main.rs src/lib.rs && cargo build --release --locked --bin tribosim

FROM debian:bookworm-slim@sha256:3783cc01769c7b2b1b83a5c5ad96c815348e28ed7da68e2e3687004faa906251
RUN useradd --system --uid 10001 --home-dir /app --shell /usr/sbin/nologin tribosim \
    && mkdir -p /data /app \
    && chown tribosim:tribosim /data
COPY --from=build /src/target/release/tribosim /usr/local/bin/tribosim
WORKDIR /app
USER tribosim
VOLUME ["/data"]
EXPOSE 8080
# No curl in the slim image: bash's /dev/tcp speaks just enough HTTP for a health check.
HEALTHCHECK --interval=30s --timeout=5s --start-period=10s --retries=3 \
    CMD ["bash", "-c", "exec 3<>/dev/tcp/127.0.0.1/8080 && printf 'GET /healthz HTTP/1.0\\r\\nHost: localhost\\r\\n\\r\\n' >&3 && head -n1 <&3 | grep -q ' 200 '"]
ENTRYPOINT ["tribosim"]
CMD ["serve", "--addr", "0.0.0.0:8080", "--data-dir", "/data"]
