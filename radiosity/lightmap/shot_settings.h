// The settings every progressive solver shares, whichever way it sees (item buffers on the GL device,
// radiosity/gpu/gl_shot_engine.h; Embree rays on the CPU, radiosity/cpu/ray_shot_engine.h): when to stop, how a
// shooter is cut into visibility regions and pieces. One struct, so the two cannot drift apart.
#pragma once

namespace cpgi {

struct ShotSettings {
  /// Stop when the unshot power is at most this fraction of the emitted power, or of the power the surfaces
  /// have reflected so far when that is less (a lamp in a dark housing), in (0, 1).
  double unshotFraction = 0.01;
  /// Stop after this many shots whatever the unshot fraction (>= 1).
  int maxShots = 100000;
  /// A shooter piece (a region, then a node of its residual pyramid, then a texel) counts as one piece
  /// for receivers farther than this many times its bounding radius; nearer receivers use its four
  /// children. >= 1.
  float farField = 2.0f;
  /// A shooter is split into visibility regions about this long (m), each seen from its own eye, so a
  /// lamp just under a ceiling's centre does not hide the whole ceiling.
  float regionSize = 1.0f;
  /// At most this many regions per chart edge, 1..4 (so at most 16 eyes' views per shot).
  int maxRegions = 2;
  /// Shots carrying at least `strongShotFraction` of the emitted power use up to `strongShotRegions`
  /// per edge (1..4; 0 = maxRegions). Such shots hold most of the light, and one eye per metres-wide
  /// region is what gives light through a door from a large shooter a hard, misplaced edge; the many
  /// weak shots after them keep the cheaper layout.
  /// Measured on seed3 (density 10, unshot 1 %, error without lamps against the reference, CPU seconds):
  /// 2 regions 16.5 % / 17.9 s; all shots 4: 12.4 % / 39.1 s; strong ≥ 1 %: 13.4 % / 20.4 s;
  /// strong ≥ 0.2 % (the default): 12.4 % / 25.5 s.
  int strongShotRegions = 4;
  double strongShotFraction = 0.002;
};

}  // namespace cpgi
