// VegetationRenderer's near blades (lod.near_blades; shaders/shared/plant_blades.h): the pipelines of the blade draw.
// Every pass draws the blades opaque: no discard and no alpha to coverage, so the depth test runs before the
// fragment shader (on lavapipe, a shader that may discard is depth-tested after it) and a view through dense grass
// shades about one layer of blades instead of every card.
#include "render/vegetation_renderer.h"

namespace sward {

uint32_t VegetationRenderer::bladeCategories() const {
    uint32_t mask = 0;
    for (uint32_t c = 0; c < std::min(scene_.vegetation.categoryCount, gpu::kMaxPlantCategories); ++c)
        if (atlasPlantKindForCategory(scene_.vegetation.categories[c].name) == AtlasPlantKind::Grass) mask |= 1u << c;
    return mask;
}

const Pipeline& VegetationRenderer::bladePipeline(PlantPass pass) {
    Pipeline& pipeline = bladePipelines_[size_t(pass)];
    if (pipeline.handle) return pipeline;
    GraphicsPipelineDesc desc;
    switch (pass) {
    case PlantPass::Main:
        desc = mainPipelineDesc("plant_blade.frag");
        desc.alphaToCoverage = false;
        desc.specialization = {/* PASS= */ gpu::kPassMain};
        break;
    case PlantPass::Truth:
    case PlantPass::TruthFlow:
        desc = truthPipelineDesc();
        desc.vertexShader = "plant_blade.vert";
        desc.fragmentShader = "plant_blade_truth.frag";
        desc.specialization = {/* PASS= */ gpu::kPassTruth};
        if (pass == PlantPass::TruthFlow) desc = truthFlowPipelineDesc(desc, formats_.truthFlow);
        break;
    case PlantPass::Shadow: // depth only: no fragment shader at all
        desc = mainPipelineDesc("");
        desc.samples = VK_SAMPLE_COUNT_1_BIT;
        desc.alphaToCoverage = false;
        desc.colorFormats = {};
        desc.depthFormat = formats_.shadowDepth;
        desc.specialization = {/* PASS= */ gpu::kPassShadow};
        desc.depthBias = -1.0f; // as the cards' casters: reversed Z, pushed away from the sun
        desc.depthBiasSlope = -1.5f;
        break;
    }
    if (pass == PlantPass::Main || pass == PlantPass::Shadow) desc.vertexShader = "plant_blade.vert";
    PipelineLayoutDesc layout = drawLayout(pass == PlantPass::Main);
    if (pass == PlantPass::TruthFlow)
        for (uint32_t binding :
             {gpu::kBindingFlowStatics, gpu::kBindingFlowDynamicsPrevious, gpu::kBindingFlowDynamicsNext})
            layout.bindings.push_back(
                layoutBinding(binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT));
    pipeline = createGraphicsPipeline(ctx_.device, desc, layout);
    return pipeline;
}

} // namespace sward
