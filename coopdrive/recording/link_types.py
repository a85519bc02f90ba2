"""What a capture's frames are: the pcap link types coopdrive reads, and GeoNetworking's ethertype. Said once for
the capture reader (capture.py) and the v2x service's pcap writer (coopdrive/v2x/pcap.py); no imports, so a service
that writes captures does not load the reader's packet library."""

# Wireshark dissects GeoNetworking on this ethertype (ETSI EN 302 636-4-1).
ETHERTYPE_GEONETWORKING = 0x8947

# tcpdump.org's link-layer header types.
LINKTYPE_ETHERNET = 1
LINKTYPE_IEEE802_11 = 105
LINKTYPE_LINUX_SLL = 113
LINKTYPE_RADIOTAP = 127
LINKTYPE_LINUX_SLL2 = 276
# GeoNetworking carried bare, with no link header: the first user link type, what a UDP radio bridge records.
LINKTYPE_USER0_BARE_GN = 147

LINK_TYPE_NAMES = {LINKTYPE_ETHERNET: "ethernet", LINKTYPE_IEEE802_11: "ieee802_11", LINKTYPE_RADIOTAP: "radiotap",
                   LINKTYPE_LINUX_SLL: "linux_sll", LINKTYPE_LINUX_SLL2: "linux_sll2",
                   LINKTYPE_USER0_BARE_GN: "bare_gn"}
LINK_TYPE_OF_NAME = {name: number for number, name in LINK_TYPE_NAMES.items()}
