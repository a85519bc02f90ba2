# One image for every coopdrive service; compose picks the service with its command.
FROM python:3.11-slim

ENV PYTHONDONTWRITEBYTECODE=1 PYTHONUNBUFFERED=1 PIP_NO_CACHE_DIR=1
WORKDIR /opt/coopdrive

COPY pyproject.toml setup.py README.md ./
COPY coopdrive ./coopdrive
COPY services ./services
COPY maps ./maps
COPY scenarios ./scenarios
COPY proto ./proto
RUN pip install . && useradd --system --uid 1000 coopdrive

USER coopdrive
ENTRYPOINT ["coopdrive"]
CMD ["--help"]
