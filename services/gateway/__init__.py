"""The gateway service: the vehicle's health and live state over HTTP (FastAPI on uvicorn)."""
