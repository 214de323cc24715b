// Layout of a compute append counter (48 bytes), shared by every kernel that appends to or
// reads a compacted list on the compute path (compact_append.comp, compact_finalize.comp, the
// traversals, the compute splat); mirrored by `AppendCounter` in crates/vkcore/src/compaction.rs.
struct CompactCounter {
    uint count;         // elements appended (may exceed capacity: overflow is visible)
    uint capacity;      // slots in the output buffer
    uint _pad0;
    uint _pad1;
    uvec4 dispatch;     // VkDispatchIndirectCommand (x, y, z) for 64-wide groups, w unused
    uvec4 draw;         // VkDrawIndirectCommand (vertexCount, instanceCount, firstVertex, firstInstance)
};
