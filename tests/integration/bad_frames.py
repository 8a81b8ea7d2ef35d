#!/usr/bin/env python3
"""Puts bad frames on a UDP CAN bus (one 16-byte Linux can_frame per datagram) for a while:
a TPDO1 of node 1 of the wrong length, frames of COB-IDs nobody uses, a truncated SDO segment,
an SDO segment with the wrong toggle bit, and datagrams that are not frames at all.
   bad_frames.py GROUP PORT SECONDS"""
import socket
import struct
import sys
import time

group, port, seconds = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
s.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_IF, socket.inet_aton("127.0.0.1"))
s.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
s.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_LOOP, 1)


def frame(cob_id, dlc, data):
    return struct.pack("<IB3x8s", cob_id, dlc, bytes(data).ljust(8, b"\0"))


bad = [
    frame(0x181, 3, [0x37, 0x06, 0x00]),            # TPDO1 of node 1, 3 bytes instead of 6
    frame(0x123, 8, [1, 2, 3, 4, 5, 6, 7, 8]),      # a COB-ID nobody uses
    frame(0x7FF, 0, []),                            # another one
    frame(0x581, 4, [0x00, 0x6D, 0x63, 0x6E]),      # an SDO segment cut to 4 bytes
    frame(0x601, 8, [0x10, 1, 2, 3, 4, 5, 6, 7]),   # a segment with toggle 1 and no transfer
    b"not a can frame",                             # 15 bytes
    frame(0x080, 9, [1]),                           # DLC above 8
]
end = time.time() + seconds
while time.time() < end:
    for datagram in bad:
        s.sendto(datagram, (group, port))
    time.sleep(0.005)
