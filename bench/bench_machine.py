"""Machine files for the benchmarks: N channels of one or two axes (X, then Z), four axes per
CAN bus on private UDP groups of a DDS domain of the bench's own, so that a bench run meets
nothing else. The axes are those of the example lathes."""

AXES_PER_BUS = 4


def machine_yaml(name, channels, axes_per_channel, cycle_us, domain, deadline_cycles=50,
                 middleware=None, axes_per_bus=AXES_PER_BUS):
    addresses = ["X", "Z", "Y", "A"][:axes_per_channel]  # a linear A: four per channel
    axes = [(f"{a}{c}", a, f"CH{c}") for c in range(1, channels + 1) for a in addresses]
    buses = (len(axes) + axes_per_bus - 1) // axes_per_bus
    lines = [
        "machine:",
        f"  name: {name}",
        f"  cycle_us: {cycle_us}",
        f"  deadline_cycles: {deadline_cycles}",
    ]
    if middleware:
        lines.append(f"  middleware: {middleware}")
    lines += [
        "buses:",
    ]
    for b in range(buses):
        lines += [
            f"  - name: can{b}",
            f"    uri: udp:239.255.{domain}.{b + 1}:{24000 + domain + 300 * b}",
            "    bitrate: 1000000",
            f"    sync_producer: {axes[b * axes_per_bus][0]}",
        ]
    lines.append("channels:")
    for c in range(1, channels + 1):
        names = ", ".join(n for n, _, ch in axes if ch == f"CH{c}")
        lines += [f"  - name: CH{c}", f"    axes: [{names}]"]
    lines.append("axes:")
    for i, (axis, address, _) in enumerate(axes):
        lines += [
            f"  - name: {axis}",
            f"    address: {address}",
            "    type: linear",
            f"    bus: can{i // axes_per_bus}",
            f"    node_id: {i % axes_per_bus + 1}",
            "    counts_per_unit: 10000",
            "    rapid_rate: 8000",
            "    max_feed: 5000",
            "    acceleration: 1500",
            "    in_position: 0.0005",
            "    drive:",
            "      max_velocity: 200",
        ]
    return "\n".join(lines) + "\n"
