#!/bin/bash
# Protocol faults: the merge with each protocol step's first iCLCM lost (one run per step, from every stack vehicle
# at once) and with a partner falling silent mid-manoeuvre; the intersection with its crossing announcement lost and
# with a partner silent; the emergency corridor with a partner silent. Each run's summary is OUT/<case>.json, and
# its service logs, with the planner's transitions and why they fired, are in OUT/<case>/.
#     tools/protocol_faults.sh [OUT] [SEED]
set -u
out=${1:-out/protocol-faults}
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
# The intersection's protocol step: the iCLCM that first announces a crossing, lost from every stack.
faults=()
for vehicle in east1 east2 west1; do
  faults+=(--fault "{type: iclcm_drop, vehicle_id: $vehicle, flag: counter_intersection, start_s: 0}")
done
"$coopdrive" run intersection --seed "$seed" --json --logs "$out/intersection_counter" "${faults[@]}" \
  > "$out/intersection_counter.json"
"$coopdrive" run intersection --seed "$seed" --json --logs "$out/intersection_silent_west1" \
  --fault "{type: partner_silent, vehicle_id: west1, start_s: 4}" > "$out/intersection_silent_west1.json"
"$coopdrive" run emergency --seed "$seed" --json --logs "$out/emergency_silent_l1" \
  --fault "{type: partner_silent, vehicle_id: l1, start_s: 12}" > "$out/emergency_silent_l1.json"
exit 0
