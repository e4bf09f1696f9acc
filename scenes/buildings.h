// Procedural buildings open to the outside (issue 12): houses with open exterior doors and glassless
// windows, two storeys joined by a straight or a spiral stair, an open-plan room, a porch. Each is built
// as a solid massing (walls, slabs, roof, steps) with the rooms and openings carved out, so every wall
// has a thickness and every surface faces exactly one room or the outside. Y up, metres.
//
// Each building carries its own answer: the rooms as boxes of empty space (the `cellvolume:` meshes of
// its hand-made cells, and what the decomposition is scored against) and every opening with the rooms it
// joins ("outside" for the exterior). Every room has a 0.6 m square lamp under its ceiling.
#pragma once

#include <string>
#include <vector>

#include "scenes/seed_scenes.h"

namespace cpgi {

struct Box3 {
  glm::vec3 lo{0.0f}, hi{0.0f};
  bool contains(const glm::vec3& p) const {
    return p.x > lo.x && p.y > lo.y && p.z > lo.z && p.x < hi.x && p.y < hi.y && p.z < hi.z;
  }
  glm::vec3 centre() const { return 0.5f * (lo + hi); }
};

/// One room: the union of its boxes of empty space.
struct BuildingRoom {
  std::string name;
  std::vector<Box3> boxes;
};

/// A hole through a wall or a slab. Its portal is the hole's cross-section at the mid-plane of `axis`.
struct BuildingOpening {
  std::string name;  ///< "front-door", "stair", "window-living", ...
  Box3 box;          ///< the hole, through the whole thickness of its wall or slab
  int axis = 0;      ///< 0, 1, 2: the axis the wall or slab is crossed along (1: a hole in a floor)
  std::string a, b;  ///< the rooms it joins (a below or west/south of b); "outside" for the exterior
  bool exterior() const { return a == "outside" || b == "outside"; }
};

struct Building {
  SeedScene seed;  ///< the scene, its cameras and hand-made cells (rooms + "outside", portals per opening)
  std::vector<BuildingRoom> rooms;  ///< interior rooms only
  std::vector<BuildingOpening> openings;
};

/// One storey, hall + living room + kitchen + bedroom; an open front door, a 2 m terrace door, glassless
/// windows.
Building makeOpenHouse();
/// Two storeys: hall, living room and kitchen below; landing and two bedrooms above; the hall and the
/// landing joined by a straight stair (16 steps along +z through a 1 × 3 m hole in the floor) or a
/// spiral stair (16 wedge steps round a column through a 2 × 2 m hole). Open front door, windows; with
/// `closedOutside` every exterior door and window is shut (the stair alone, as older decompositions saw
/// a house whose doors were closed by hand).
Building makeTwoStoreyHouse(bool spiral, bool closedOutside = false);
/// The spiral house furnished as a real model comes (~34k triangles: furniture, books, a balustrade,
/// terrain), lit by KHR_lights_punctual point lights and a spot instead of emissive panels.
Building makeFurnishedHouse();
/// Two storeys: a double-height living room overlooked by the upper gallery above a 1 m balustrade along
/// their whole shared wall (4.7 × 1.5 m open), the gallery reached from the hall by the straight stair.
Building makeGalleryHouse();
/// One L-shaped open-plan living, dining and kitchen room with a kitchen island, a bedroom and a bathroom.
Building makeOpenPlanHouse();
/// The house of makeOpenHouse's size with a roofed porch on posts in front of its open front door.
Building makePorchHouse();

/// The two-storey house in the shape an IFC export has (issue 46): glazed windows (closed), two open
/// exterior doors, doorways without leaves, furniture, a glass shower enclosure and a hollow wardrobe, ten
/// rooms; the stair from the hall to the landing is "straight" (a flight with its waist, open beneath),
/// "open-riser" (4 cm treads alone), "l" (two flights round a quarter landing) or "spiral".
/// Throws std::invalid_argument for another stair.
Building makeIfcLikeHouse(const std::string& stair);
/// The IFC-like house with a gallery: the living room rises through both storeys (no room1 or room2 over
/// it) and the landing overlooks it above a 1 m parapet along their whole 6 m shared wall (6 × 1.7 m
/// open), or with `balustrade` over a 0.9 m balustrade of spindles on the landing floor's edge (6 × 2.7 m
/// open between and above them); the straight stair; room3 reached through bath2; eight rooms.
Building makeIfcGalleryHouse(bool balustrade = false);

/// "house-open", "house-stair", "house-spiral", "open-plan", "porch", "house-stair-closed",
/// "house-spiral-closed", "house-gallery", "house-furnished", "ifc-house", "ifc-house-open-riser",
/// "ifc-house-l-stair", "ifc-house-spiral", "ifc-house-gallery", "ifc-house-gallery-balustrade".
const std::vector<std::string>& buildingNames();
/// Throws std::invalid_argument for a name not in buildingNames().
Building makeBuilding(const std::string& name);

}  // namespace cpgi
