#pragma once
// The report's sections, in the order the report shows them. Each builder adds its section(s)
// only when the study has the data, and a note where an older store lacks what a part needs.
#include "reports/document.hpp"
#include "reports/study_data.hpp"

namespace seedcal::reports {

void add_answer_section(const StudyData& d, Document& doc);        // the answer: values, intervals, lab, model
void add_inputs_section(const StudyData& d, Document& doc);        // study file, parameters, targets
void add_screening_sections(const StudyData& d, Document& doc);    // PB design; effects + Pareto chart
void add_ascent_section(const StudyData& d, Document& doc);        // steepest ascent path and the box
void add_surrogate_sections(const StudyData& d, Document& doc);    // RS design; ANOVA and fit statistics
void add_surface_plot_sections(const StudyData& d, Document& doc); // contour of the surface; LOO plot
void add_posterior_plot_section(const StudyData& d, Document& doc); // posterior density, 95 % region, intervals
void add_curve_section(const StudyData& d, Document& doc);          // the point on the solution curve
void add_confirmation_section(const StudyData& d, Document& doc);  // optimiser and confirmation trace
void add_summary_section(const StudyData& d, Document& doc);       // calibrated values, confirmation, cost
void add_verification_sections(const StudyData& d, Document& doc); // verification; model selection
void add_scenes_section(const StudyData& d, Document& doc);        // scene pictures and shear curves

}  // namespace seedcal::reports
