"""The router's access control (Zenoh 1.x `access_control`) from the bus grants: default deny, and for each
certificate's common name exactly what its grant allows.

Flows are the router's: `ingress` is what a client sends it, `egress` what it forwards to a client. So a grant's puts
are ingress puts, and its subscriptions are ingress subscriber declarations plus the egress puts that feed them.
Two things every holder of the vehicle's CA gets, being needed by the runtime and revealing no data:
- egress subscriber declarations under the vehicle: a publisher learns whether anyone hears it (coopdrive.bus.session
  puts only then);
- presence: liveliness tokens of the bus (watching them, asking for them), as the gateway, actuation and
  `coopdrive health` do;
- being asked for its info by a query on every service's (`_info/*`, as the recorder asks): the query carries nothing,
  and only what a grant's queryables answer comes back.
"""

from __future__ import annotations

from coopdrive.bus.bus_grant import BusGrant
from coopdrive.bus.keys import KeyLayout

HEARS_SUBSCRIBERS = "hears who subscribes"
SEES_PRESENCE = "sees who is alive"
IS_ASKED_WITH_OTHERS = "is asked for its info with the others"


def access_control(grants: list[BusGrant], vehicle_id: str, layout: KeyLayout | None = None,
                   heard: tuple[str, ...] = ()) -> dict:
    """The `access_control` section of the router's config; `heard`: keys besides the vehicle's whose subscribers
    every holder may learn of (a simulated bus's world and step markers)."""
    layout = layout or KeyLayout()
    rules = [
        _rule(HEARS_SUBSCRIBERS, "egress", ["declare_subscriber"],
              (layout.all_topics(vehicle_id), layout.step_done(vehicle_id, "**"), *heard)),
        _rule(SEES_PRESENCE, "ingress", ["declare_liveliness_subscriber", "liveliness_query"],
              (layout.all_liveliness(),)),
        _rule(f"{SEES_PRESENCE} (tokens)", "egress", ["liveliness_token"], (layout.all_liveliness(),)),
        _rule(IS_ASKED_WITH_OTHERS, "egress", ["query"], (layout.service_info(vehicle_id, "*"),)),
    ]
    subjects, policies = [], []
    for grant in grants:
        own = [rule for rule in _grant_rules(grant) if rule["key_exprs"]]
        rules += own
        subjects.append({"id": grant.subject, "cert_common_names": [grant.subject]})
        policies.append({"id": grant.subject, "subjects": [grant.subject],
                         "rules": [HEARS_SUBSCRIBERS, SEES_PRESENCE, f"{SEES_PRESENCE} (tokens)", IS_ASKED_WITH_OTHERS,
                                   *(rule["id"] for rule in own)]})
    return {"enabled": True, "default_permission": "deny", "rules": rules, "subjects": subjects,
            "policies": policies}


def _grant_rules(grant: BusGrant) -> list[dict]:
    name = grant.subject
    return [
        _rule(f"{name} publishes", "ingress", ["put"], grant.puts),
        _rule(f"{name} subscribes", "ingress", ["declare_subscriber"], grant.subscriptions),
        _rule(f"{name} receives", "egress", ["put"], grant.subscriptions),
        _rule(f"{name} is alive", "ingress", ["liveliness_token"], grant.tokens),
        _rule(f"{name} answers", "ingress", ["declare_queryable", "reply"], grant.queryables),
        _rule(f"{name} is asked", "egress", ["query"], grant.queryables),
        _rule(f"{name} asks", "ingress", ["query"], grant.queries),
        _rule(f"{name} is answered", "egress", ["reply"], grant.queries),
    ]


def _rule(rule_id: str, flow: str, messages: list[str], key_exprs: tuple[str, ...]) -> dict:
    return {"id": rule_id, "permission": "allow", "flows": [flow], "messages": messages, "key_exprs": list(key_exprs)}
