# tribosim serve in a container.
#
#   docker build -t tribosim .
#   docker run -d -p 8080:8080 -v tribosim-data:/data -e TRIBOSIM_TOKEN=<secret> tribosim
#
# The server listens on 0.0.0.0 inside the container, which is not loopback, so it refuses
# to start without a token: pass TRIBOSIM_TOKEN (or append `--token ...` to the command).
# Clients then send `Authorization: Bearer <secret>` on every /api/v1 call; /, /healthz and
# /api/v1/openapi.yaml stay open. Jobs and results live in the /data volume; on
# `docker stop` (SIGTERM) running jobs are interrupted and run again at the next start.

FROM rust:1.95-slim-bookworm AS build
WORKDIR /src
COPY Cargo.toml Cargo.lock ./
COPY src ./src
# Compiled into the binary (served at /api/v1/openapi.yaml).
COPY openapi.yaml ./
RUN cargo build --release --locked --bin tribosim

FROM debian:bookworm-slim
RUN useradd --system --uid 10001 --home-dir /app --shell /usr/sbin/nologin tribosim \
    && mkdir -p /data /app \
    && chown tribosim:tribosim /data
COPY --from=build /src/target/release/tribosim /usr/local/bin/tribosim
COPY static /app/static
WORKDIR /app
USER tribosim
VOLUME ["/data"]
EXPOSE 8080
# No curl in the slim image: bash's /dev/tcp speaks just enough HTTP for a health check.
HEALTHCHECK --interval=30s --timeout=5s --start-period=10s --retries=3 \
    CMD ["bash", "-c", "exec 3<>/dev/tcp/127.0.0.1/8080 && printf 'GET /healthz HTTP/1.0\\r\\nHost: localhost\\r\\n\\r\\n' >&3 && head -n1 <&3 | grep -q ' 200 '"]
ENTRYPOINT ["tribosim"]
CMD ["serve", "--addr", "0.0.0.0:8080", "--data-dir", "/data"]
