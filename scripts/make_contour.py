#!/usr/bin/env python3
"""Writes paths/ur5_deburring_contour.csv: one deburring pass around a rounded rectangle in a
horizontal plane in front of the UR5-class example arm (urdf/ur5_class.urdf), tool orientation
fixed, as tool poses in the base frame (t_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad).

The pass starts and ends at rest: the path length s(t) follows a trapezoidal speed profile
(0.5 s ramps, 0.08 m/s cruise). One row every 20 ms.

Usage: scripts/make_contour.py > paths/ur5_deburring_contour.csv
"""
import math

CENTER = (0.45, 0.10, 0.25)  # m, base frame
HALF = (0.08, 0.05)  # half width (x) and half height (y) of the rectangle, m
RADIUS = 0.025  # corner radius, m
RPY = (-3.0845960172932765, 0.5542066365534857, 2.701366908522486)  # FK of a reachable pose
SPEED = 0.08  # m/s
RAMP = 0.5  # s
STEP = 0.02  # s between rows


def contour_point(s):
    """Point at arc length s (m) along the rounded rectangle, counter-clockwise from the middle of
    the right edge."""
    ax, ay = HALF[0] - RADIUS, HALF[1] - RADIUS  # straight half-lengths
    arc = math.pi / 2 * RADIUS
    pieces = []  # (length, function of local u in [0, length])
    cx, cy = CENTER[0], CENTER[1]
    pieces.append((ay, lambda u: (cx + HALF[0], cy + u)))
    pieces.append((arc, lambda u: (cx + ax + RADIUS * math.cos(u / RADIUS),
                                   cy + ay + RADIUS * math.sin(u / RADIUS))))
    pieces.append((2 * ax, lambda u: (cx + ax - u, cy + HALF[1])))
    pieces.append((arc, lambda u: (cx - ax + RADIUS * math.cos(math.pi / 2 + u / RADIUS),
                                   cy + ay + RADIUS * math.sin(math.pi / 2 + u / RADIUS))))
    pieces.append((2 * ay, lambda u: (cx - HALF[0], cy + ay - u)))
    pieces.append((arc, lambda u: (cx - ax + RADIUS * math.cos(math.pi + u / RADIUS),
                                   cy - ay + RADIUS * math.sin(math.pi + u / RADIUS))))
    pieces.append((2 * ax, lambda u: (cx - ax + u, cy - HALF[1])))
    pieces.append((arc, lambda u: (cx + ax + RADIUS * math.cos(1.5 * math.pi + u / RADIUS),
                                   cy - ay + RADIUS * math.sin(1.5 * math.pi + u / RADIUS))))
    pieces.append((ay, lambda u: (cx + HALF[0], cy - ay + u)))
    for length, f in pieces:
        if s <= length:
            return f(s)
        s -= length
    return pieces[-1][1](pieces[-1][0])


def perimeter():
    ax, ay = HALF[0] - RADIUS, HALF[1] - RADIUS
    return 4 * ax + 4 * ay + 2 * math.pi * RADIUS


def main():
    total = perimeter()
    cruise = (total - SPEED * RAMP) / SPEED  # time at full speed
    duration = cruise + 2 * RAMP
    a = SPEED / RAMP

    def s_of(t):
        if t < RAMP:
            return 0.5 * a * t * t
        if t < RAMP + cruise:
            return 0.5 * a * RAMP * RAMP + SPEED * (t - RAMP)
        r = duration - t
        return total - 0.5 * a * r * r

    print("t_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad")
    n = int(math.floor(duration / STEP + 1e-9))
    times = [k * STEP for k in range(n + 1)]
    if duration - times[-1] > 1e-9:
        times.append(duration)
    for t in times:
        x, y = contour_point(min(total, max(0.0, s_of(t))))
        print(f"{t:.6f},{x:.9f},{y:.9f},{CENTER[2]:.9f},{RPY[0]:.12f},{RPY[1]:.12f},{RPY[2]:.12f}")


if __name__ == "__main__":
    main()
