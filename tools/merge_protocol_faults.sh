#!/bin/bash
# The merge with each protocol step's first iCLCM lost (one run per step, from every stack vehicle at once), then
# with a partner falling silent mid-manoeuvre. Each run's summary is OUT/<case>.json and its service logs, with
# the planner's transitions and why they fired, are in OUT/<case>/.
#     tools/merge_protocol_faults.sh [OUT] [SEED]
set -u
out=${1:-out/merge-protocol-faults}
seed=${2:-1}
coopdrive=${COOPDRIVE:-.venv/bin/coopdrive}
mkdir -p "$out"
for flag in forward_id backward_id acknowledge_flag merge_request merge_safe_to_merge merge_flag merge_flag_head \
            merge_flag_tail; do
  faults=()
  for vehicle in a1 a2 a3 b1 b2 b3; do
    faults+=(--fault "{type: iclcm_drop, vehicle_id: $vehicle, flag: $flag, start_s: 0}")
  done
  "$coopdrive" run merge --seed "$seed" --json --logs "$out/$flag" "${faults[@]}" > "$out/$flag.json"
done
"$coopdrive" run merge --seed "$seed" --json --logs "$out/silent_b2" \
  --fault "{type: partner_silent, vehicle_id: b2, start_s: 12}" > "$out/silent_b2.json"
exit 0
