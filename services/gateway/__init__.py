"""The gateway service: the vehicle's health and live state over HTTP (FastAPI on uvicorn).

- service.py: wiring; bus handlers feed the store, the HTTP server reads it.
- state_store.py: StateStore, latest messages, liveliness and wall-time rates (thread-safe, no network).
- reports.py: /health and /state responses from a store snapshot; ages on the vehicle clock.
- models.py: the pydantic response models (bus messages stay proto, served as proto3 JSON).
- api.py: the FastAPI routes, bearer-token roles, /ws and the HMI (static/).
- view_models.py, views.py: /v2x/stations, /scene, /planner and the /ws live frames.
- auth.py: TokenBook, tokens to names and roles; commands.py: CommandDesk, commands to bus messages, logged.
- live.py: LiveBroadcaster, per-client bounded queues that drop frames for slow clients.
- metrics.py: GatewayMetrics, Prometheus gauges; recording.py: GatewayRecording (POST /recording).
- server.py: HttpServerThread, uvicorn on a daemon thread with a bounded stop.
- config.py: GatewayConfig.
"""
