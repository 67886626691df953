// Host loop of the image-space tracing step (detail/layer_trace_body.inl):
// the trace names a texel, `fetch` reads every layer's depth there, the
// shared step consumes them. A GLSL caller writes the same loop around its
// own texture reads (docs/secondary-rays.md, "Image-space tracing").
#pragma once

#include "kernel.hpp"

namespace blurcull {

// Traces `seg` (kernel<Real>::layer_segment) through the layers 0 ..
// layer_count - 1 of view `v`. fetch(layer, x, y) returns the view depth
// stored at texel (x, y) of that layer (+infinity, any value >= far or NaN
// for no surface). At most layer_step_count(v, seg) steps.
template <class Real, class Fetch>
typename kernel<Real>::LayerHit trace_layers(const typename kernel<Real>::LayerView& v,
                                             const typename kernel<Real>::LayerSegment& seg, int layer_count,
                                             Real thickness, const Fetch& fetch) {
    using K = kernel<Real>;
    typename K::LayerTrace t = K::layer_trace_begin(v, seg, layer_count, thickness);
    for (int k = 0; k < t.steps; ++k) {
        if (t.done) break;
        Real depths[BC_LAYERS_MAX] = {};
        for (int l = 0; l < t.layers; ++l) depths[l] = fetch(l, t.x, t.y);
        t = K::layer_trace_step(v, seg, t, depths);
    }
    return t.hit;
}

}  // namespace blurcull
