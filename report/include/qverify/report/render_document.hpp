#pragma once
/// \file render_document.hpp
/// The render reports written out: the `qverify-render/1` documents
/// (docs/json-documents.md) and the text `qverify render` prints.

#include <qverify/render/render.hpp>

#include <nlohmann/json.hpp>

#include <string>

namespace qverify {

nlohmann::ordered_json render_json(const render::RenderReport& report);
std::string render_text(const render::RenderReport& report);

nlohmann::ordered_json compare_json(const render::CompareReport& report);
std::string compare_text(const render::CompareReport& report);

}  // namespace qverify
