// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// "Did you mean": the known word closest to a misspelt one (a plugin name, a command), so a
// message can offer it.
#ifndef MJFORMATION_CONFIG_NEAREST_WORD_HPP_
#define MJFORMATION_CONFIG_NEAREST_WORD_HPP_

#include <string>
#include <vector>

namespace mjf::runner {

// Edits (insert, delete, substitute, swap two neighbours: the optimal string alignment
// distance) that turn `a` into `b`, letters compared without case.
size_t EditDistance(const std::string& a, const std::string& b);

// The candidate nearest `word` when it is near enough to be a slip: at most 1 edit for words of
// up to 5 letters, 2 up to 11, else 3 (ties: the first candidate). Empty when none is, or when
// `word` is itself a candidate.
std::string NearestWord(const std::string& word, const std::vector<std::string>& candidates);

// "; did you mean 'run'?" for NearestWord's answer, or "" when there is none.
std::string DidYouMean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_NEAREST_WORD_HPP_
