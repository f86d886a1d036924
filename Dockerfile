# The app as README.md installs it (a normal `pip install .`), run by an unprivileged user; the classroom's
# database lives in the volume /data (docs/deployment.md).
FROM python:3.11-slim
ENV PYTHONDONTWRITEBYTECODE=1 \
    PIP_NO_CACHE_DIR=1 \
    MDL_DATA_DIR=/data \
    NUMBA_CACHE_DIR=/var/cache/mdl/numba
RUN useradd --system --home-dir /nonexistent --shell /usr/sbin/nologin mdl \
    && mkdir -p /data /var/cache/mdl/numba \
    && chown mdl:mdl /data /var/cache/mdl/numba
WORKDIR /src
COPY pyproject.toml README.md ./
COPY server ./server
COPY web ./web
COPY content ./content
COPY bench/results ./bench/results
RUN python3 -m pip install . && rm -rf /src
WORKDIR /data
USER mdl
# compile the numba kernels once, into the image (a container then starts in about a second)
RUN python3 -m server.core.warm_up
VOLUME ["/data"]
EXPOSE 8000
# Behind a reverse proxy, name its address as the container sees it, or every student counts as the proxy:
#   docker run -v mdl-data:/data -e MDL_FORWARDED_ALLOW_IPS=172.17.0.1 -e MDL_DATABASE_URL=postgresql://…
CMD ["python3", "-m", "server", "--host", "0.0.0.0", "--port", "8000"]
