"""Metrics that count events: integers wherever a run's metrics are printed or written."""

from coopdrive.runtime.barrier import MESSAGES_GIVEN_UP_COUNTER

COUNT_METRICS = ("collisions", "safety_circle_violations", "id_switches", "truth_samples", "truth_missing_samples",
                 "participants_lost", "automation_lost", "v2x_packets_sent", "v2x_packets_received",
                 "v2x_packets_rejected", "gnss_jumps", "v2x_rejected_untrusted", "v2x_rejected_certificate_expired",
                 "v2v_unheard_stacks", "service_crashes", "service_restarts", "v2x_reception_pairs", "safe_stops",
                 "hard_brakes", "phantom_brakes", "signal_red_light_violations", "signal_red_light_violations_scripted",
                 "signal_crossings",
                 MESSAGES_GIVEN_UP_COUNTER)
