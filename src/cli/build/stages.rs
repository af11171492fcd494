//! The stages of one build, in the order `Build::run` calls them: load, derive, render (the
//! documents once, each renderer printing them), typeset, then the summary of what was written.

use super::{Build, NotBuilt, typeset_with_progress};
use crate::base::format::count;
use crate::pipeline::{self, SceneReport};
use crate::render::pdf::PdfSource;
use crate::render::pdf::batch::PdfStore;
use crate::render::{Rendered, SiteFiles};
use crate::scene::{Course, Scene};
use std::path::{Path, PathBuf};

/// A failure other than the scenes': the course file, the output folder, the templates, the
/// writing.
pub(super) fn other(e: impl Into<anyhow::Error>) -> NotBuilt {
    NotBuilt::Other(e.into())
}

/// How many scenes the cache gave whole, and how many only their symbolic part.
pub(super) struct FromCache {
    pub whole: usize,
    pub symbolic: usize,
}

/// What rendering left for the rest of the build, the reports and documents freed.
pub(super) struct Rendering {
    pub rendered: Rendered,
    /// A roster's papers, and its `variants.csv`.
    pub papers: Option<(Vec<PdfSource>, Vec<u8>)>,
    pub warnings: Vec<String>,
    /// The checks that failed, located.
    pub failures: Vec<String>,
    /// How many scenes failed a check.
    pub failed: usize,
    pub scenes: usize,
}

/// What typesetting the site's PDFs did.
pub(super) struct Typesetting {
    pub typeset: usize,
    pub from_cache: usize,
    pub pending: Vec<String>,
    pub failed: Vec<String>,
}

impl Build {
    /// The course file and the scenes, refused before anything is derived (so a refused build
    /// touches nothing): the output folder, then every scene file.
    pub(super) fn load(&self) -> Result<(Course, Vec<Scene>), NotBuilt> {
        let mut course = crate::scene::Course::load(&self.course_file).map_err(other)?;
        // The papers name each student's variant: the site, which may be published, then
        // holds no variant's answers (the roster's own key is among the papers).
        course.answers_private = self.roster.is_some();
        // The inputs are the scene files themselves, and the folders named.
        let files = self.check_output().map_err(NotBuilt::Other)?;
        let scenes = crate::scene::load_all(&files)
            .map_err(|errors| NotBuilt::Scenes(errors.iter().map(ToString::to_string).collect()))?;
        super::super::warn(&scenes);
        if self.whole_course {
            let lectures = scenes.iter().map(|s| s.notes.lecture.as_str()).collect();
            if let Some(e) = course.unused_lecture(&lectures) {
                return Err(NotBuilt::Scenes(vec![e.to_string()]));
            }
        }
        Ok((course, scenes))
    }

    /// Every scene derived and checked, or taken from the cache.
    pub(super) fn derive(
        &self,
        scenes: Vec<Scene>,
    ) -> Result<(Vec<SceneReport>, FromCache), NotBuilt> {
        let (reports, errors) = match &self.cache {
            Some(cache) => super::run_all(scenes, self.fidelity, cache),
            None => super::run_all(scenes, self.fidelity, &pipeline::NoStore),
        };
        if !errors.is_empty() {
            return Err(NotBuilt::Derive(errors));
        }
        let count =
            |kind: pipeline::FromCache| reports.iter().filter(|r| r.from_cache == kind).count();
        let cached = FromCache {
            whole: count(pipeline::FromCache::Everything),
            symbolic: count(pipeline::FromCache::Symbolic),
        };
        Ok((reports, cached))
    }

    /// The documents, made once from the reports; each renderer prints them. The reports and
    /// documents are freed before anything is typeset, which is the build's peak in memory.
    pub(super) fn render(
        &self,
        reports: Vec<SceneReport>,
        course: &Course,
        templates: &crate::render::TemplateTexts,
    ) -> Result<Rendering, NotBuilt> {
        let documents = crate::document::course::documents(&reports, course);
        // The papers' sources before anything is rendered or typeset, so that a roster the
        // sheets cannot serve is refused at once.
        let papers = match &self.roster {
            Some((roster, _, seed)) if !self.pdfs_later => Some(
                crate::render::pdf::roster_documents(&documents, course, roster, *seed)
                    .map_err(other)?,
            ),
            _ => None,
        };
        let cx = crate::render::Context {
            course,
            templates,
            timings: self.timings,
            memo: match &self.cache {
                Some(cache) => cache,
                None => &crate::render::memo::Forget,
            },
            keys: Default::default(),
            pdfs_later: self.pdfs_later,
        };
        let mut rendered = crate::render::render(&documents, &cx).map_err(other)?;
        let mut warnings = Vec::new();
        // What the renderers made for the cache is not held past this point.
        let kept = std::mem::take(&mut rendered.kept);
        if let Some(cache) = &self.cache
            && let Err(e) = cache.keep_rendered(&kept)
        {
            warnings.push(format!("the cache is not updated: {e}"));
        }
        drop(kept);
        // The summary's figures are taken from the reports, which are then freed with the
        // documents: typesetting, the build's peak in memory, needs neither (docs/performance.md,
        // "Typesetting within a memory budget"). Freeing them takes 10 ms: on another thread
        // when nothing is typeset, as in the page-first build that `serve` waits for; else here,
        // where the memory freed can be given back before typesetting.
        // A step not yet recorded fails `check`, not a build: the author may be writing it.
        let (new_steps, failures): (Vec<_>, Vec<_>) = reports
            .iter()
            .flat_map(crate::report::failures)
            .partition(|f| f.new_step);
        let failures: Vec<String> = failures.into_iter().map(|f| f.text).collect();
        let failed = reports
            .iter()
            .filter(|r| !r.verification.passed_but_for_new_steps())
            .count();
        if !new_steps.is_empty() {
            eprintln!(
                "mechbook: note: {} not yet recorded, which `check` fails on: once you have \
                 reviewed them, `mechbook check --bless` records them",
                count(new_steps.len(), "step")
            );
        }
        let scenes = reports.len();
        drop(documents);
        if self.pdfs_later {
            std::thread::spawn(move || drop(reports));
        } else {
            drop(reports);
        }
        Ok(Rendering {
            rendered,
            papers,
            warnings,
            failures,
            failed,
            scenes,
        })
    }

    /// The site's PDFs typeset (or taken from the cache) into `site`; with `--pdfs-later`, only
    /// those in the cache.
    pub(super) fn typeset_site(
        &self,
        rendered: &mut Rendered,
        site: &mut SiteFiles,
        warnings: &mut Vec<String>,
    ) -> Result<Typesetting, NotBuilt> {
        let mut in_site = |path: PathBuf, pdf: Vec<u8>| {
            site.insert(path, pdf);
            Ok::<(), crate::site::SiteError>(())
        };
        let store = self.pdf_store("site");
        let store = store.as_ref().map(|s| s as &dyn PdfStore);
        let pdfs = if self.pdfs_later {
            crate::render::pdf::batch::from_cache_only(&rendered.typeset, store, &mut in_site)
        } else {
            typeset_with_progress(&rendered.typeset, store, &mut in_site)
        }
        .map_err(other)?;
        let mut pending = pdfs.pending;
        pending.extend(std::mem::take(&mut rendered.later));
        warnings.extend(pdfs.warnings);
        Ok(Typesetting {
            typeset: pdfs.made - pdfs.from_cache,
            from_cache: pdfs.from_cache,
            pending,
            // A document Typst cannot set fails the build, but the HTML site and the other
            // PDFs are still written.
            failed: pdfs.failed,
        })
    }

    /// The cache's PDFs under `prefix`, when the build has a cache.
    fn pdf_store<'a>(&'a self, prefix: &'a str) -> Option<crate::site::pdfs::CachedPdfs<'a>> {
        let cache = self.cache.as_ref()?;
        Some(crate::site::pdfs::CachedPdfs { cache, prefix })
    }

    /// A roster's papers, each written as soon as it is made, into a folder that takes the
    /// papers' place once the site is written: a class's papers are not all held at once.
    pub(super) fn typeset_papers(
        &self,
        papers: Option<(Vec<PdfSource>, Vec<u8>)>,
        warnings: &mut Vec<String>,
        failed: &mut Vec<String>,
    ) -> Result<Option<(&Path, crate::site::Staging, usize)>, NotBuilt> {
        let (Some((roster, dir, _)), Some((sources, csv))) = (&self.roster, papers) else {
            return Ok(None);
        };
        let staging = crate::site::Staging::begin(dir).map_err(other)?;
        let store = self.pdf_store("papers");
        let store = store.as_ref().map(|s| s as &dyn PdfStore);
        let made =
            typeset_with_progress(&sources, store, &mut |path, pdf| staging.write(&path, &pdf))
                .map_err(other)?;
        warnings.extend(made.warnings);
        failed.extend(made.failed);
        staging
            .write(Path::new("variants.csv"), &csv)
            .map_err(other)?;
        Ok(Some((dir.as_path(), staging, roster.students.len())))
    }

    /// The line that says what the build wrote, and what failed.
    pub(super) fn summary(
        &self,
        site: &SiteFiles,
        made: &Rendering,
        cached: &FromCache,
        pdfs: &Typesetting,
        papers: Option<(&Path, usize)>,
        seconds: f64,
    ) -> String {
        let handouts = site.keys().filter(|p| p.starts_with("handouts")).count();
        let plots = site.keys().filter(|p| p.starts_with("plots")).count();
        let (typeset, pdf_cached) = (pdfs.typeset, pdfs.from_cache);
        let pdf = if crate::document::files::PDFS && self.pdfs_later {
            format!(
                ", {} from the cache ({} left to typeset next)",
                count(pdf_cached, "PDF"),
                pdfs.pending.len()
            )
        } else if crate::document::files::PDFS {
            format!(
                ", {} ({typeset} typeset, {pdf_cached} from the cache)",
                count(typeset + pdf_cached, "PDF")
            )
        } else {
            String::new()
        };
        let papers = papers.map_or(String::new(), |(dir, students)| {
            format!(
                "; {} and their key into {} (the site leaves out the answer keys and LMS \
                 quizzes, since each paper names its variant)",
                match students {
                    1 => "1 student's paper".to_string(),
                    n => format!("{n} students' papers"),
                },
                dir.display()
            )
        });
        let (scene_count, failed) = (made.scenes, made.failed);
        let summary = format!(
            "built {}, {} and {}{pdf} from {} ({} from the cache, {} re-run numerically on cached symbolic results) into {} in {:.2} s{papers}{}{}",
            count(scene_count + 1, "page"),
            count(plots, "plot"),
            count(handouts, "handout"),
            count(scene_count, "scene"),
            cached.whole,
            cached.symbolic,
            self.out.display(),
            seconds,
            super::super::peak_memory_mib()
                .map_or(String::new(), |m| format!(", peak memory {m:.0} MiB")),
            if failed > 0 {
                format!(
                    "; {} FAILED their checks (run `mechbook check`)",
                    count(failed, "scene")
                )
            } else {
                String::new()
            }
        );
        if pdfs.failed.is_empty() {
            summary
        } else {
            format!(
                "{summary}; {} FAILED to typeset (above)",
                count(pdfs.failed.len(), "PDF")
            )
        }
    }
}
