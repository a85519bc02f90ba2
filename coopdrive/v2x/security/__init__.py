"""Security envelope of V2X packets: IEEE 1609.2 signed data as profiled by ETSI TS 103 097 v1.3.1 (OER), and the
older TS 103 097 v1.2.1 SecuredMessage of GN version 0 roadside units (v121_*.py, judged by inspection too).

Public API (pure logic, no Zenoh):
- `inspection.PacketInspector(store).inspect(packet, now_tai_us | None)` -> InspectedPacket(security:
  SecurityResult(signed, signer, signer_digest, verified, fresh, trusted, reason, ...), unsecured_packet);
  `inspection.mode_drop_reason(mode, result)`: what a mode drops. The contract is in inspection.py.
- `verifier.SecurityVerifier(store)`: `.verify(packet, now_tai_us) -> (ok, reason, signer_digest)`,
  `.open(...)` also returns the unsecured GN packet; `.rejected_by_reason` counts every failure.
- `signer.SecuredPacketSigner(tickets)`: `.sign(packet, now_tai_us)`, `.request_full_certificate()`,
  `.rotate_pseudonym()` (ticket, station id and MAC together; refused under `.manoeuvre_lock(name)`).
- `layer.ModeSecurityLayer(mode, verifier, signer)`: what `V2xPacketCodec(security=...)` calls; `.seal(packet)`.
- `profile.SecurityMode`: off, sign_only, sign_and_verify, verify_required; PSIDs 36 CAM, 37 DENM, 127 iCLCM.
- `store.CertificateStore`: trusted roots, known authorities, cache of tickets heard in full.
- `pki.create_test_pki(dir, vehicles)`, `pki.pki_init(dir, vehicles)` (for `coopdrive pki init DIR`),
  faults `create_untrusted_pki`, `issue_expired_ticket`, `tamper_packet`; `load_test_pki(dir)`.
"""
