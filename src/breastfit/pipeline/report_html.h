#pragma once
/// \file report.html: the registration report for a reader, typically the surgeon — one
/// self-contained HTML file (inline CSS, images embedded as base64 PNG data: URIs, no scripts,
/// no network) with:
///  - the scan, the template, the units, and the warnings in a coloured box at the top;
///  - how to read the report;
///  - the registration (time, iterations, stopping reason), the paper's surface and landmark
///    errors (with a per-landmark table), the transferred drawings (length, share on the scan,
///    mean model-to-scan distance, confidence with its rule) and the breast measurements;
///  - the six figures of report_figures.h (front, obliques and sides, distance);
///  - what the other output files are and what to open them with;
///  - traceability (RegisterResult::provenance): version, inputs with SHA-256, the UTC start
///    time and command line, the effective fit options (collapsed, as --config JSON).
/// Deterministic: the same result gives the same bytes; between runs of the same registration
/// only time_s and the run rows (`<tbody class="run">`: start time, command line) differ.
#include <filesystem>
#include <string>

#include "breastfit/pipeline/register_scan.h"
#include "breastfit/pipeline/report_figures.h"

namespace breastfit::pipeline {

/// Escapes & < > " ' for HTML text and attribute values.
std::string html_escape(const std::string& text);

/// The report as one HTML document.
/// \param template_name  the template's name (model::RiggedModel::name)
/// \param figures        report_figures(result, model) (embedded in this order)
std::string report_html(const RegisterResult& result, const std::string& template_name,
                        const ReportFigures& figures);

/// Renders the figures (report_figures: over `layers` when given, drawn beforehand with the same
/// options) and writes report_html to `path`.
/// \throws IoError if the file cannot be written; InvalidInput for invalid options
void write_report_html(const std::filesystem::path& path, const RegisterResult& result,
                       const model::RiggedModel& model, const ReportFigureOptions& options = {},
                       const std::shared_ptr<ReportLayerDrawing>& layers = nullptr);

}  // namespace breastfit::pipeline
