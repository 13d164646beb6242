#ifndef VPLKIT_ELEMENT_COUNT_GLSL
#define VPLKIT_ELEMENT_COUNT_GLSL

// Element counts that may live on the GPU (stages/element_count.hpp). A pass that takes a count
// pushes the capacity it was dispatched for and a word index: kHostElementCount when the host
// knew the count (it is the capacity), otherwise the count is that word of the bound count
// buffer, written by an earlier pass of the same submission (a VPL source's counter), clamped
// to the capacity because producers count attempts past their space. The host then never reads
// the count back between producing the elements and consuming them.
//
// Declare the buffer with VPLKIT_DECLARE_ELEMENT_COUNT(binding) after the shader's other
// bindings; it also defines element_count(capacity, word).

const uint kHostElementCount = 0xffffffffu;

#define VPLKIT_DECLARE_ELEMENT_COUNT(binding_index)                                                       \
    layout(std430, set = 0, binding = binding_index) readonly buffer ElementCountBuffer {                 \
        uint words[];                                                                                     \
    } element_count_words;                                                                                \
    uint element_count(uint capacity, uint word) {                                                        \
        return word == kHostElementCount ? capacity : min(element_count_words.words[word], capacity);     \
    }

#endif
