"""The V2X library: GeoNetworking, BTP, ITS PDUs (ASN.1 UPER), their mapping to the stack's messages, the TS 103 097
security envelope and PKI, ITS time and the CAM/iCLCM generation rules. Used by the v2x service, its command line
tools and the simulator; it imports no service."""
