// Sequence parameter set parsing for width, height and frame rate: H.264 clause 7.3.2.1.1
// with VUI (Annex E.1.1), H.265 clause 7.3.2.2 with VUI (Annex E.2.1). Every field before
// the VUI timing is walked (scaling lists, reference picture sets) because the bit
// position depends on it; nothing else is interpreted.
#include <algorithm>

#include "video/bit_reader.hpp"
#include "video/nal.hpp"

namespace gimbal::video {

namespace {

std::optional<double> rate(std::uint32_t num_units_in_tick, std::uint32_t time_scale,
                           double ticks_per_frame) {
    if (num_units_in_tick == 0 || time_scale == 0) return std::nullopt;
    return static_cast<double>(time_scale) / (ticks_per_frame * num_units_in_tick);
}

void skip_h264_scaling_list(BitReader& r, int size) {
    int last = 8;
    int next = 8;
    for (int j = 0; j < size && !r.failed(); ++j) {
        if (next != 0) {
            const std::int32_t delta = r.se();  // delta_scale: -128..127
            if (delta < -128 || delta > 127) return r.fail();
            next = (last + delta + 256) % 256;
        }
        last = next == 0 ? last : next;
    }
}

bool h264_high_profile(std::uint32_t profile) {
    constexpr std::uint32_t high[] = {100, 110, 122, 244, 44, 83, 86, 118, 128, 138, 139, 134, 135};
    return std::find(std::begin(high), std::end(high), profile) != std::end(high);
}

// Aspect ratio, overscan, video signal type and chroma location: the VUI fields both codecs
// share up to where they differ.
void skip_vui_head(BitReader& r) {
    if (r.bit()) {                         // aspect_ratio_info_present_flag
        if (r.bits(8) == 255) r.skip(32);  // Extended_SAR: sar_width, sar_height
    }
    if (r.bit()) r.skip(1);       // overscan_info_present_flag -> overscan_appropriate_flag
    if (r.bit()) {                // video_signal_type_present_flag
        r.skip(4);                // video_format, video_full_range_flag
        if (r.bit()) r.skip(24);  // colour_description_present_flag -> 3 x u(8)
    }
    if (r.bit()) {  // chroma_loc_info_present_flag
        r.ue();
        r.ue();
    }
}

std::optional<VideoFormat> parse_h264(ByteView nal) {
    const Bytes rbsp = unescape_rbsp(nal.subspan(1));
    BitReader r(rbsp);
    const std::uint32_t profile = r.bits(8);
    r.skip(16);  // constraint flags, level_idc
    r.ue();      // seq_parameter_set_id
    std::uint32_t chroma_format_idc = 1;
    bool separate_colour_plane = false;
    if (h264_high_profile(profile)) {
        chroma_format_idc = r.ue();
        if (chroma_format_idc > 3) return std::nullopt;
        if (chroma_format_idc == 3) separate_colour_plane = r.bit() != 0;
        r.ue();         // bit_depth_luma_minus8
        r.ue();         // bit_depth_chroma_minus8
        r.skip(1);      // qpprime_y_zero_transform_bypass_flag
        if (r.bit()) {  // seq_scaling_matrix_present_flag
            const int lists = chroma_format_idc != 3 ? 8 : 12;
            for (int i = 0; i < lists && !r.failed(); ++i) {
                if (r.bit()) skip_h264_scaling_list(r, i < 6 ? 16 : 64);
            }
        }
    }
    r.ue();  // log2_max_frame_num_minus4
    const std::uint32_t poc_type = r.ue();
    if (poc_type == 0) {
        r.ue();  // log2_max_pic_order_cnt_lsb_minus4
    } else if (poc_type == 1) {
        r.skip(1);  // delta_pic_order_always_zero_flag
        r.se();     // offset_for_non_ref_pic
        r.se();     // offset_for_top_to_bottom_field
        const std::uint32_t cycle = r.ue();
        if (cycle > 255) return std::nullopt;
        for (std::uint32_t i = 0; i < cycle && !r.failed(); ++i) r.se();
    } else if (poc_type != 2) {
        return std::nullopt;
    }
    r.ue();     // max_num_ref_frames
    r.skip(1);  // gaps_in_frame_num_value_allowed_flag
    const std::uint64_t width_mbs = std::uint64_t{r.ue()} + 1;
    const std::uint64_t height_map_units = std::uint64_t{r.ue()} + 1;
    const std::uint32_t frame_mbs_only = r.bit();
    if (!frame_mbs_only) r.skip(1);  // mb_adaptive_frame_field_flag
    r.skip(1);                       // direct_8x8_inference_flag
    std::uint64_t crop[4] = {0, 0, 0, 0};
    if (r.bit()) {
        for (auto& c : crop) c = r.ue();
    }
    std::optional<double> fps;
    if (r.bit()) {  // vui_parameters_present_flag
        skip_vui_head(r);
        if (r.bit()) {  // timing_info_present_flag
            const std::uint32_t num_units_in_tick = r.bits(32);
            const std::uint32_t time_scale = r.bits(32);
            // Two ticks per frame: the H.264 clock counts fields (E.2.1).
            if (!r.failed()) fps = rate(num_units_in_tick, time_scale, 2.0);
        }
    }
    if (r.failed()) return std::nullopt;
    const bool mono = chroma_format_idc == 0 || separate_colour_plane;
    const std::uint64_t sub_w = mono || chroma_format_idc == 3 ? 1 : 2;
    const std::uint64_t sub_h = mono || chroma_format_idc != 1 ? 1 : 2;
    const std::uint64_t crop_x = sub_w;
    const std::uint64_t crop_y = sub_h * (2 - frame_mbs_only);
    const std::uint64_t w = width_mbs * 16;
    const std::uint64_t h = (2 - frame_mbs_only) * height_map_units * 16;
    const std::uint64_t cw = crop_x * (crop[0] + crop[1]);
    const std::uint64_t ch = crop_y * (crop[2] + crop[3]);
    if (cw >= w || ch >= h || w > 65536 || h > 65536) return std::nullopt;
    return VideoFormat{static_cast<int>(w - cw), static_cast<int>(h - ch), fps};
}

void skip_h265_profile_tier_level(BitReader& r, std::uint32_t max_sub_layers_minus1) {
    r.skip(88);  // general profile space/tier/idc, 32 compatibility flags, 48 constraint bits
    r.skip(8);   // general_level_idc
    bool profile_present[8] = {};
    bool level_present[8] = {};
    for (std::uint32_t i = 0; i < max_sub_layers_minus1; ++i) {
        profile_present[i] = r.bit() != 0;
        level_present[i] = r.bit() != 0;
    }
    if (max_sub_layers_minus1 > 0) r.skip(2 * (8 - max_sub_layers_minus1));  // reserved
    for (std::uint32_t i = 0; i < max_sub_layers_minus1; ++i) {
        if (profile_present[i]) r.skip(88);
        if (level_present[i]) r.skip(8);
    }
}

void skip_h265_scaling_list_data(BitReader& r) {
    for (int size_id = 0; size_id < 4; ++size_id) {
        for (int matrix_id = 0; matrix_id < 6; matrix_id += size_id == 3 ? 3 : 1) {
            if (!r.bit()) {  // scaling_list_pred_mode_flag
                r.ue();      // scaling_list_pred_matrix_id_delta
                continue;
            }
            const int coefs = std::min(64, 1 << (4 + (size_id << 1)));
            if (size_id > 1) r.se();  // scaling_list_dc_coef_minus8
            for (int i = 0; i < coefs && !r.failed(); ++i) r.se();
        }
    }
}

// st_ref_pic_set (7.3.7) as it appears in the SPS; returns NumDeltaPocs of the set.
std::uint32_t skip_h265_st_ref_pic_set(BitReader& r, std::uint32_t idx,
                                       const std::vector<std::uint32_t>& num_delta_pocs) {
    if (idx != 0 && r.bit()) {  // inter_ref_pic_set_prediction_flag
        r.skip(1);              // delta_rps_sign
        r.ue();                 // abs_delta_rps_minus1
        std::uint32_t count = 0;
        for (std::uint32_t j = 0; j <= num_delta_pocs[idx - 1] && !r.failed(); ++j) {
            const bool used = r.bit() != 0;
            const bool use_delta = used || r.bit() != 0;
            if (use_delta) ++count;
        }
        return count;
    }
    const std::uint32_t negative = r.ue();
    const std::uint32_t positive = r.ue();
    if (negative > 16 || positive > 16) {
        r.skip(1u << 30);  // impossible sizes: mark the reader failed
        return 0;
    }
    for (std::uint32_t i = 0; i < negative + positive; ++i) {
        r.ue();     // delta_poc_s{0,1}_minus1
        r.skip(1);  // used_by_curr_pic_s{0,1}_flag
    }
    return negative + positive;
}

std::optional<VideoFormat> parse_h265(ByteView nal) {
    if (nal.size() < 2) return std::nullopt;
    const Bytes rbsp = unescape_rbsp(nal.subspan(2));
    BitReader r(rbsp);
    r.skip(4);  // sps_video_parameter_set_id
    const std::uint32_t max_sub_layers_minus1 = r.bits(3);
    if (max_sub_layers_minus1 > 6) return std::nullopt;
    r.skip(1);  // sps_temporal_id_nesting_flag
    skip_h265_profile_tier_level(r, max_sub_layers_minus1);
    r.ue();  // sps_seq_parameter_set_id
    const std::uint32_t chroma_format_idc = r.ue();
    if (chroma_format_idc > 3) return std::nullopt;
    bool separate_colour_plane = false;
    if (chroma_format_idc == 3) separate_colour_plane = r.bit() != 0;
    const std::uint64_t w = r.ue();
    const std::uint64_t h = r.ue();
    std::uint64_t win[4] = {0, 0, 0, 0};
    if (r.bit()) {  // conformance_window_flag
        for (auto& c : win) c = r.ue();
    }
    r.ue();  // bit_depth_luma_minus8
    r.ue();  // bit_depth_chroma_minus8
    const std::uint32_t log2_max_poc_lsb = r.ue() + 4;
    if (log2_max_poc_lsb > 16) return std::nullopt;
    const bool sub_layer_ordering_info = r.bit() != 0;
    for (std::uint32_t i = sub_layer_ordering_info ? 0 : max_sub_layers_minus1;
         i <= max_sub_layers_minus1; ++i) {
        r.ue();  // sps_max_dec_pic_buffering_minus1
        r.ue();  // sps_max_num_reorder_pics
        r.ue();  // sps_max_latency_increase_plus1
    }
    for (int i = 0; i < 6; ++i) r.ue();  // coding/transform block sizes, hierarchy depths
    if (r.bit() && r.bit()) skip_h265_scaling_list_data(r);  // enabled, sps data present
    r.skip(2);      // amp_enabled_flag, sample_adaptive_offset_enabled_flag
    if (r.bit()) {  // pcm_enabled_flag
        r.skip(8);  // pcm sample bit depths
        r.ue();
        r.ue();
        r.skip(1);  // pcm_loop_filter_disabled_flag
    }
    const std::uint32_t num_st_rps = r.ue();
    if (num_st_rps > 64) return std::nullopt;
    std::vector<std::uint32_t> num_delta_pocs;
    for (std::uint32_t i = 0; i < num_st_rps && !r.failed(); ++i) {
        num_delta_pocs.push_back(skip_h265_st_ref_pic_set(r, i, num_delta_pocs));
    }
    if (r.bit()) {  // long_term_ref_pics_present_flag
        const std::uint32_t n = r.ue();
        if (n > 32) return std::nullopt;
        for (std::uint32_t i = 0; i < n; ++i) r.skip(log2_max_poc_lsb + 1);
    }
    r.skip(2);  // sps_temporal_mvp_enabled_flag, strong_intra_smoothing_enabled_flag
    std::optional<double> fps;
    if (r.bit()) {  // vui_parameters_present_flag
        skip_vui_head(r);
        r.skip(3);      // neutral_chroma_indication, field_seq, frame_field_info_present
        if (r.bit()) {  // default_display_window_flag
            for (int i = 0; i < 4; ++i) r.ue();
        }
        if (r.bit()) {  // vui_timing_info_present_flag
            const std::uint32_t num_units_in_tick = r.bits(32);
            const std::uint32_t time_scale = r.bits(32);
            if (!r.failed()) fps = rate(num_units_in_tick, time_scale, 1.0);
        }
    }
    if (r.failed()) return std::nullopt;
    const bool mono = chroma_format_idc == 0 || separate_colour_plane;
    const std::uint64_t sub_w = mono || chroma_format_idc == 3 ? 1 : 2;
    const std::uint64_t sub_h = mono || chroma_format_idc != 1 ? 1 : 2;
    const std::uint64_t cw = sub_w * (win[0] + win[1]);
    const std::uint64_t ch = sub_h * (win[2] + win[3]);
    if (w == 0 || h == 0 || cw >= w || ch >= h || w > 65536 || h > 65536) return std::nullopt;
    return VideoFormat{static_cast<int>(w - cw), static_cast<int>(h - ch), fps};
}

}  // namespace

std::optional<VideoFormat> parse_sps(Codec codec, ByteView sps_nal) {
    if (sps_nal.empty()) return std::nullopt;
    if (nal_type(codec, sps_nal) != (codec == Codec::h264 ? h264::sps : h265::sps))
        return std::nullopt;
    return codec == Codec::h264 ? parse_h264(sps_nal) : parse_h265(sps_nal);
}

}  // namespace gimbal::video
