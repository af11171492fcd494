//! Typesetting, tested on small documents: an author's text is never markup, a wide formula is
//! broken across lines, the checks find text past the edge and characters with no glyph, and
//! the same markup gives the same bytes.

use super::PdfSource;
use super::markup::{Markup, preamble};
use super::typeset::typeset;
use crate::notation::Tex;
use crate::scene::{Course, Paper};

fn course(paper: Paper) -> Course {
    let mut c = Course::parse(
        "title = \"Course\"\n",
        std::path::Path::new("mechbook.toml"),
    )
    .unwrap();
    c.paper = paper;
    c
}

fn doc(paper: Paper, body: impl FnOnce(&mut Markup)) -> PdfSource {
    let mut m = Markup::new(preamble(&course(paper), "Title", "Head", "Right"));
    body(&mut m);
    m.source("pdf/test.pdf", Vec::new())
}

/// The PDF's text streams are compressed; its page size is in the clear.
fn media_box(pdf: &[u8]) -> String {
    let s = String::from_utf8_lossy(pdf);
    let at = s.find("/MediaBox").expect("a MediaBox");
    s[at..].chars().take_while(|c| *c != ']').collect()
}

#[test]
fn an_authors_text_is_text_however_it_reads_as_markup() {
    let title = "A *bold* _claim_ // #let x = 1 <label> @ref [x] \\ $";
    let out = typeset(&doc(Paper::A4, |m| {
        m.heading(1, "Notes").unwrap();
        m.text(title);
        m.heading(2, "The $\\beta$ of a top, #1").unwrap();
    }))
    .expect("typesets");
    assert_eq!(out.pages, 1);
    assert!(out.missing_glyphs.is_empty() && out.past_the_edge.is_empty());
}

#[test]
fn a_formula_wider_than_the_paper_is_broken_onto_it_and_text_past_the_edge_is_found() {
    let tex = Tex::read(&vec!["a"; 160].join(" + ")).unwrap();
    let long = tex.to_typst().unwrap();
    let fitted = typeset(&doc(Paper::A4, |m| {
        m.block(&tex, "a plus a and so on").unwrap();
    }))
    .unwrap();
    assert!(fitted.past_the_edge.is_empty());
    // The same formula set without `fit`, in a block wider than the paper, runs off it; the
    // scene whose part it is in is named.
    let unbroken = typeset(&doc(Paper::A4, |m| {
        m.scene_part(
            std::path::Path::new("x.toml"),
            7,
            crate::notation::Names::none(),
            |m| {
                m.raw("#block(width: 400mm)[#set math.equation(alt: \"a sum\");$ ")
                    .raw(&long)
                    .raw(" $]");
            },
        );
    }))
    .unwrap();
    assert_eq!(unbroken.past_the_edge, vec![1]);
    assert_eq!(unbroken.past_the_edge_in, vec!["x.toml:7".to_string()]);
}

/// A formula short enough is set without `measure` (`narrow`), and gives the bytes the measured
/// `fit` gives; a long one is still measured.
#[test]
fn a_short_formula_set_without_measuring_gives_the_measured_bytes() {
    let short = [
        r"I_{xx} = \frac{2}{5} m a^{2}",
        r"\vec{I} = \begin{pmatrix}1 & 0 \\ 0 & 1\end{pmatrix}",
        r"p_{\psi} = I_{3} \left(\dot{\psi} + \dot{\phi} \cos\theta\right)",
    ]
    .map(|latex| Tex::read(latex).unwrap());
    let long = Tex::read(&vec!["a"; 160].join(" + ")).unwrap();
    for paper in [Paper::A4, Paper::Letter] {
        let mut markups = Vec::new();
        let unmeasured = typeset(&doc(paper, |m| {
            for f in &short {
                m.block(f, "a formula").unwrap();
            }
            m.block(&long, "a sum").unwrap();
            markups.push(m.text.clone());
        }))
        .unwrap();
        let measured = typeset(&doc(paper, |m| {
            for f in &short {
                let f = f.to_typst().unwrap();
                m.raw("\n#[#set math.equation(alt: \"a formula\");\n#fit($ ")
                    .raw(&f)
                    .raw(" $, $display(")
                    .raw(&f)
                    .raw(")$)\n]\n");
            }
            m.block(&long, "a sum").unwrap();
        }))
        .unwrap();
        let markup = &markups[0];
        assert_eq!(markup.matches("#narrow($").count(), short.len(), "{markup}");
        assert_eq!(markup.matches("#fit($").count(), 1);
        assert!(
            unmeasured.pdf == measured.pdf,
            "{paper:?}: the bytes differ"
        );
    }
}

#[test]
fn a_character_no_font_has_is_named() {
    let out = typeset(&doc(Paper::A4, |m| {
        m.text("Name: 王小明, Zoë Ørsted");
    }))
    .unwrap();
    assert_eq!(out.missing_glyphs, vec!['小', '明', '王']);
}

#[test]
fn the_same_markup_gives_the_same_bytes_on_the_courses_paper() {
    let a4 = doc(Paper::A4, |m| {
        m.text("Hello ")
            .inline("frac(1, 12) m a^(2)", "1 over 12 m a squared");
    });
    let (one, two) = (typeset(&a4).unwrap(), typeset(&a4).unwrap());
    assert_eq!(one.pdf, two.pdf);
    let text = String::from_utf8_lossy(&one.pdf);
    assert!(!text.contains("/CreationDate") && !text.contains("/ModDate"));
    // 595.276 × 841.89 pt is A4; 612 × 792 pt is US Letter.
    assert!(
        media_box(&one.pdf).contains("595.2"),
        "{}",
        media_box(&one.pdf)
    );
    let letter = typeset(&doc(Paper::Letter, |m| {
        m.text("Hello");
    }))
    .unwrap();
    assert!(
        media_box(&letter.pdf).contains("612"),
        "{}",
        media_box(&letter.pdf)
    );
}

#[test]
fn a_roster_field_is_quoted_and_never_a_spreadsheet_formula() {
    use super::csv_field;
    crate::base::assert_each(
        csv_field,
        &[
            ("Ada", "Ada"),
            ("Lovelace, Ada", "\"Lovelace, Ada\""),
            ("Alan \"Turing\"", "\"Alan \"\"Turing\"\"\""),
            ("=HYPERLINK(1)", "'=HYPERLINK(1)"),
            ("@sum, x", "\"'@sum, x\""),
        ],
    );
}

#[test]
fn every_kind_of_name_a_scene_may_write_is_typeset() {
    // A letter, then letters, digits and single underscores (scene::validate's rule): digits
    // then letters (`I1cone`, `d2U`) once read as an unknown variable and failed the build.
    let names = [
        "I1cone",
        "d2U",
        "I1c",
        "w1s",
        "x_1y",
        "Omega2a",
        "phi2",
        "Ixxy",
        "alpha_beta",
        "a1_b2",
        "wd3",
        "theta",
        "L",
        "Lag",
        "p_phi",
        "k12x3",
    ];
    let out = typeset(&doc(Paper::A4, |m| {
        for name in names {
            let e = crate::cas::Expr::sym(name);
            m.inline(
                &super::markup::expr(&e, crate::notation::Names::none()),
                &e.to_tex(crate::notation::Names::none()).spoken(),
            );
            let rate = crate::cas::Expr::sym(&format!("{name}'"));
            m.inline(
                &super::markup::expr(&rate, crate::notation::Names::none()),
                &rate.to_tex(crate::notation::Names::none()).spoken(),
            );
        }
    }));
    assert!(
        out.is_ok(),
        "{}",
        out.err().map(|e| e.to_string()).unwrap_or_default()
    );
}

/// The PDFs' sources of the scenes' documents, as a build renders them (no cache).
fn pdf_sources(reports: &[crate::pipeline::SceneReport]) -> Vec<PdfSource> {
    let course = Course::default();
    let documents = crate::document::course::documents(reports, &course);
    let cx = crate::render::Context {
        course: &course,
        templates: &Default::default(),
        timings: false,
        memo: &crate::render::memo::Forget,
        keys: Default::default(),
        pdfs_later: false,
    };
    crate::render::render(&documents, &cx).unwrap().typeset
}

/// Each scene's part of a lecture's documents is marked with its file and line (the `id`'s in
/// a handout, the `[problem]`'s on a sheet), so a Typst error there is reported at the scene.
#[test]
fn each_scenes_part_of_a_document_is_marked_with_its_line() {
    const BOX: &str = "id = \"b\"\ntitle = \"A box\"\nnotes = { lecture = \"x\" }\n\
        symbols = { m = \"mass\", a = \"side\" }\n\
        [[body]]\nkind = \"box\"\nsize = [\"a\", \"a\", \"a\"]\nmass = \"m\"\norigin = \"centre\"\n\
        [outputs]\nwant = [\"inertia_tensor\"]\n\
        [numeric]\nvalues = { m = 1.0, a = 1.0 }\n\
        [problem]\nstatement = \"A cube of mass {m} kg and side {a} m.\"\n\
        answers = [\"mass\"]\n\
        [variants]\ncount = 2\nm = [\"2\", \"3\"]\na = [\"1\"]\n";
    let scene = crate::scene::Scene::parse(BOX, std::path::Path::new("b.toml")).unwrap();
    let reports = [crate::pipeline::run_scene(scene, None).unwrap()];
    let docs = pdf_sources(&reports);
    let marks: Vec<(&str, Vec<&str>)> = docs
        .iter()
        .map(|d| {
            let names = d
                .origins
                .iter()
                .filter(|(_, s)| !s.is_empty())
                .map(|(_, s)| s.as_str())
                .collect();
            (d.path.as_str(), names)
        })
        .collect();
    assert_eq!(
        marks,
        [
            ("pdf/lecture-x-student.pdf", vec![]),
            ("pdf/lecture-x-instructor.pdf", vec!["b.toml:1"]),
            ("pdf/lecture-x-problems-student.pdf", vec!["b.toml:14"; 2]),
            ("pdf/lecture-x-problems-key.pdf", vec!["b.toml:14"; 2]),
        ]
    );
    // A mark starts the scene's part: its heading, with the scene's title, follows.
    let instructor = &docs[1];
    let (at, _) = &instructor.origins[0];
    let part = instructor.markup[*at..].trim_start();
    assert!(
        part.starts_with("#heading(level: 2)[#\"A box\""),
        "{}",
        &part[..80]
    );
}

/// Whatever the one LaTeX reader reads is set by Typst too: each element of its tree (letters,
/// numbers, operator names, accents, fonts, scripts above and below, fractions, roots, sized
/// and paired brackets, spaces, matrices, cases, aligned lines, negations) in one formula each,
/// the page's MathML made from the same tree.
#[test]
fn every_element_the_reader_reads_is_typeset() {
    let forms = [
        r"\vec{\omega}_x \cdot \hat n = \sqrt[3]{\alpha} \ne \Omega",
        r"\mathrm{kg\,m^2}",
        r"^2",
        r"\left.\frac{dL}{dt}\right|_{\mathrm{body}}",
        r"\mathbb{R} \mathcal{L} \mathbf{F} \boldsymbol\tau \mathit{x} \mathsf{y} \mathtt{z}",
        r"\begin{cases} a & x > 0 \\ b & x \le 0 \end{cases}",
        r"\begin{bmatrix} 1 & 2 \\ 3 & 4 \end{bmatrix} \begin{vmatrix} a \end{vmatrix} \begin{matrix} b \end{matrix}",
        r"\begin{aligned} a &= b \\ &= c \end{aligned}",
        r"\sum_{i=1}^{n} \int_0^\infty \lim_{x \to 0} \prod_k \oint",
        r"\operatorname{tr} \sin^2 x \ln y \exp z \det A",
        r"a\!b\,c\:d\;e\quad f\qquad g~h\ i \hspace{1cm} j",
        r"\overbrace{a + b} \underbrace{c} \overline{d} \tilde e \dot f \ddot g \bar h",
        r"\{a\} |x| \|v\| \langle a \rangle \Bigl( b \Bigr) \bigl[ c \bigr]",
        r"x^{y^{z}}_{i} f'(x) 1{,}000 \% \# \& \$ \_",
        r"\not< \not\in \pm \mp \times \div \approx \equiv \propto \parallel \perp",
        r"\displaystyle\frac12 \textstyle\frac34 \scriptstyle x",
        r#"\text{with words, (brackets); and a "quote"}"#,
        r"\frac{(}{)} \sqrt{)} ( [ \{",
        r"\begin{matrix} \rm a & b \\ \bf c & \it d \end{matrix} x \rm y",
    ];
    for form in forms {
        let tex = crate::notation::Tex::read(form).unwrap_or_else(|e| panic!("{form}: {e}"));
        tex.to_mathml(false)
            .unwrap_or_else(|e| panic!("{form}: {e}"));
        let typst = tex.to_typst().unwrap_or_else(|e| panic!("{form}: {e}"));
        let out = typeset(&doc(Paper::A4, |m| {
            m.inline(&typst, &tex.spoken());
        }));
        let out = out.unwrap_or_else(|e| panic!("{form} as {typst}: {e}"));
        assert!(
            out.missing_glyphs.is_empty(),
            "{form}: {:?}",
            out.missing_glyphs
        );
    }
}

#[test]
fn a_sheet_or_a_class_key_is_one_document_up_to_200_then_parts_of_200() {
    use super::parts;
    assert_eq!(parts(1), vec![0..1]);
    assert_eq!(parts(200), vec![0..200]);
    assert_eq!(parts(201), vec![0..200, 200..201]);
    let all = parts(10_000);
    assert_eq!(all.len(), 50);
    // Every variant in one part, in order.
    assert!(all.windows(2).all(|w| w[0].end == w[1].start));
    assert_eq!((all[0].start, all[49].end), (0, 10_000));
    assert_eq!(super::which_of("variant", 401, 401), "variant 401");
    assert_eq!(super::which_of("student", 201, 400), "students 201 to 400");
}

/// The Typst markup of tests/course's "Bodies of revolution" student handout (the cone and the
/// hemisphere), as a snapshot: a change in how the PDFs print a formula, a verdict or a table
/// is a reviewable diff (`cargo insta review`).
#[test]
fn the_typst_markup_of_a_handout() {
    let reports: Vec<_> = [
        "tests/course/bodies/03-cone.toml",
        "tests/course/bodies/04-hemisphere.toml",
    ]
    .iter()
    .map(|f| {
        let scene = crate::scene::Scene::from_file(std::path::Path::new(f)).unwrap();
        crate::pipeline::run_scene(scene, None).unwrap()
    })
    .collect();
    let docs = pdf_sources(&reports);
    let student = docs
        .iter()
        .find(|d| d.path.ends_with("-student.pdf"))
        .expect("a student's handout");
    insta::assert_snapshot!("typst_student_handout", student.markup);
}

/// A unit on paper is said as the page's alternative text says it: "per", "squared".
#[test]
fn a_unit_is_said_as_the_page_says_it() {
    use super::quantities::said_unit;
    assert_eq!(said_unit("m/s^2"), " m per s squared");
    assert_eq!(said_unit("kg m^2"), " kg m squared");
    assert_eq!(said_unit("kg*m^2/s"), " kg m squared per s");
}
