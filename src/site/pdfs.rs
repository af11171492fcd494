//! The build cache as the PDFs' store (`render::pdf::batch`): each document's PDF and what was
//! said of it, under a prefix of the cache's names (`site`, `papers`).

use super::cache::{Cache, Lookup};
use crate::render::pdf::batch::{PdfStore, StoreError, Stored};

/// The cache's PDFs of one kind of document: the site's, or a roster's papers.
pub struct CachedPdfs<'a> {
    pub cache: &'a Cache,
    pub prefix: &'a str,
}

impl CachedPdfs<'_> {
    /// The name of a document's entry in the cache.
    fn name(&self, path: &str) -> String {
        format!(
            "{}-{}",
            self.prefix,
            path.trim_end_matches(".pdf").replace('/', "-")
        )
    }
}

impl PdfStore for CachedPdfs<'_> {
    fn load(&self, path: &str, inputs: u64) -> Stored {
        let name = self.name(path);
        match self.cache.load_pdf(&name, inputs) {
            Lookup::Hit(pdf) => {
                let warnings = match self.cache.load_pdf_warnings(&name, inputs) {
                    Lookup::Hit(said) => String::from_utf8_lossy(&said)
                        .lines()
                        .map(str::to_string)
                        .collect(),
                    _ => Vec::new(),
                };
                Stored::Hit { pdf, warnings }
            }
            Lookup::Miss => Stored::Miss,
            Lookup::Damaged(entry, why) => Stored::Damaged(format!(
                "the cache entry {} is damaged ({why})",
                entry.display()
            )),
        }
    }

    fn store(
        &self,
        path: &str,
        inputs: u64,
        pdf: &[u8],
        warnings: &[String],
    ) -> Result<(), StoreError> {
        let name = self.name(path);
        // The warnings first: a PDF found in the cache has its warnings there too.
        if !warnings.is_empty() {
            self.cache.store_pdf_warnings(&name, inputs, warnings)?;
        }
        self.cache.store_pdf(&name, inputs, pdf)?;
        Ok(())
    }
}
