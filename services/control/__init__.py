"""The control service: longitudinal and lateral control laws as plain logic (service.py wires them to the bus).

- longitudinal.LongitudinalController: per target CACC / dCACC / ACC, cruise, min-select, comfort and jerk
  limits, a separate TTC emergency path. Laws: cacc (ours), ploeg, acc (Rajamani, ours), dcacc, cruise, drivertive.
- lateral.LateralController: Heudiasyc PD, Stanley or pure pursuit, quintic lane change, angle/rate limits.
- profiles: car and truck VehicleProfile; config.ControlConfig; inputs: Scene + BehaviourRequest to targets.
- string_stability: |V_i / V_i-1 (jw)| of each following law with lag and dead time, and its plot.
"""
