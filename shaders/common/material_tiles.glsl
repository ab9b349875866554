// The visibility pipeline's per-material tile lists (material_tiles.comp writes them,
// material_tile.vert reads them; render/pipeline/src/visibility_pipeline.cpp sizes them):
// the eye's buffer in MATERIAL_TILE×MATERIAL_TILE texel tiles; per material slot one
// indirect draw command (6 vertices, one instance per tile) and a list of the tiles that
// hold the material. Slots past the last hold every material from there on, so a scene
// with more materials still renders, each of those drawing their shared list.
// The compositor defines MATERIAL_TILE and MATERIAL_SLOTS (kMaterialTile and
// kMaterialSlots in visibility_pipeline.cpp, the one place they are set).
#if !defined(MATERIAL_TILE) || !defined(MATERIAL_SLOTS)
#error "MATERIAL_TILE and MATERIAL_SLOTS are defined by the compositor"
#endif

struct TileDrawCommand {
  uint count, instance_count, first, base_instance;  // glDrawArraysIndirect's layout
};

// The slot of a material index (Scene::materials; materials.size() is the default).
uint material_slot(uint material) { return min(material, uint(MATERIAL_SLOTS - 1)); }
